package io.robomw.it.security;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.ArrayList;
import java.util.List;

/**
 * A sniffer in the middle of TCP connections, as someone who can read the traffic would be: it
 * listens on a loopback port, passes every connection on to the real server, and keeps a copy of
 * what went each way. One thread per direction per connection, all named and stopped by {@link #close()}.
 */
final class TcpTap implements AutoCloseable {

    private final ServerSocket server;
    private final int target;
    private final ByteArrayOutputStream toServer = new ByteArrayOutputStream();
    private final ByteArrayOutputStream toClient = new ByteArrayOutputStream();
    private final List<Socket> sockets = new ArrayList<>();
    private final Thread acceptor;

    /** @param target the real server's loopback port */
    TcpTap(int target) throws IOException {
        this.target = target;
        this.server = new ServerSocket();
        server.bind(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
        this.acceptor = new Thread(this::accept, "tcp-tap-accept");
        acceptor.setDaemon(true);
        acceptor.start();
    }

    /** @return the port clients use instead of the server's */
    int port() {
        return server.getLocalPort();
    }

    /** @return what clients sent the server so far */
    byte[] sentToServer() {
        synchronized (toServer) {
            return toServer.toByteArray();
        }
    }

    /** @return what the server sent clients so far */
    byte[] sentToClients() {
        synchronized (toClient) {
            return toClient.toByteArray();
        }
    }

    private void accept() {
        try {
            while (true) {
                Socket client = server.accept();
                Socket upstream = new Socket(InetAddress.getLoopbackAddress(), target);
                synchronized (sockets) {
                    sockets.add(client);
                    sockets.add(upstream);
                }
                pump(client.getInputStream(), upstream.getOutputStream(), toServer, "tcp-tap-up");
                pump(upstream.getInputStream(), client.getOutputStream(), toClient, "tcp-tap-down");
            }
        } catch (IOException closed) {
            // the tap was closed
        }
    }

    private static void pump(InputStream in, OutputStream out, ByteArrayOutputStream copy, String name) {
        Thread t = new Thread(() -> {
            byte[] buf = new byte[8192];
            try {
                for (int n; (n = in.read(buf)) > 0; ) {
                    synchronized (copy) {
                        copy.write(buf, 0, n);
                    }
                    out.write(buf, 0, n);
                    out.flush();
                }
            } catch (IOException e) {
                // one side closed
            } finally {
                try {
                    out.close();
                } catch (IOException e) {
                    // closing anyway
                }
            }
        }, name);
        t.setDaemon(true);
        t.start();
    }

    @Override
    public void close() throws IOException {
        server.close();
        synchronized (sockets) {
            for (Socket s : sockets) {
                s.close();
            }
        }
    }
}
