package io.robomw.it.net;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.io.PrintStream;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * Delay for a {@link NetLab}, where the kernel has no {@code netem}: a user-space TCP relay, run in
 * a namespace of its own ({@code ip netns exec NS java ... DelayRelay ...}). It listens on
 * {@code LISTEN-IP:PORT} for each {@code PORT=TARGET-IP:TARGET-PORT} it is given and forwards every
 * connection to its target, holding each chunk of bytes, in each direction, for the delay before
 * passing it on (in order: a chunk read at t leaves at t + delay). So a peer that connects to the
 * relay's address instead of the target's sees a link with that one-way latency, its bandwidth
 * untouched. A relay rather than a decorator of RoboMW's transports: it delays the real sockets of
 * every protocol (RMI, the agent wire, messaging, MQTT) without changing the code under test.
 * Prints {@code READY} once it listens; ends on end of input or SIGTERM.
 * Arguments: {@code DELAY-MS LISTEN-IP PORT=TARGET-IP:TARGET-PORT...}.
 */
public final class DelayRelay {

    private record Chunk(long dueNanos, byte[] bytes) {
    }

    private DelayRelay() {
    }

    /**
     * @param args delay in milliseconds, the address to listen on, and one or more forwards
     * @throws IOException if a port cannot be listened on
     */
    public static void main(String[] args) throws IOException {
        long delayNanos = TimeUnit.MILLISECONDS.toNanos(Long.parseLong(args[0]));
        String listen = args[1];
        for (String forward : Arrays.copyOfRange(args, 2, args.length)) {
            int port = Integer.parseInt(forward.substring(0, forward.indexOf('=')));
            String target = forward.substring(forward.indexOf('=') + 1);
            InetSocketAddress to = new InetSocketAddress(target.substring(0, target.lastIndexOf(':')), Integer.parseInt(target.substring(target.lastIndexOf(':') + 1)));
            ServerSocket server = new ServerSocket();
            server.setReuseAddress(true);
            server.bind(new InetSocketAddress(listen, port));
            start("relay-accept-" + port, () -> accept(server, to, delayNanos));
        }
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        out.println("READY");
        System.in.transferTo(OutputStream.nullOutputStream()); // until the test ends it
        System.exit(0);
    }

    private static void accept(ServerSocket server, InetSocketAddress to, long delayNanos) {
        while (true) {
            try {
                Socket in = server.accept();
                Socket out = new Socket();
                try {
                    out.connect(to, 10_000);
                } catch (IOException e) {
                    in.close();
                    out.close();
                    continue;
                }
                in.setTcpNoDelay(true);
                out.setTcpNoDelay(true);
                pipe(in, out, delayNanos, "relay-" + in.getPort() + "-out");
                pipe(out, in, delayNanos, "relay-" + in.getPort() + "-back");
            } catch (IOException e) {
                return;
            }
        }
    }

    /** Two threads: one reads and stamps chunks, one writes each when it is due. Closing either end closes both. */
    private static void pipe(Socket from, Socket to, long delayNanos, String name) {
        BlockingQueue<Chunk> queue = new LinkedBlockingQueue<>();
        Chunk end = new Chunk(0, null);
        start(name + "-read", () -> {
            byte[] buf = new byte[64 * 1024];
            try (InputStream in = from.getInputStream()) {
                for (int n; (n = in.read(buf)) > 0; ) {
                    queue.add(new Chunk(System.nanoTime() + delayNanos, Arrays.copyOf(buf, n)));
                }
            } catch (IOException e) {
                // the connection ended
            }
            queue.add(end);
        });
        start(name + "-write", () -> {
            try (OutputStream out = to.getOutputStream()) {
                while (true) {
                    Chunk c = queue.take();
                    if (c == end) {
                        break;
                    }
                    long wait = c.dueNanos() - System.nanoTime();
                    if (wait > 0) {
                        TimeUnit.NANOSECONDS.sleep(wait); // the link's latency: this chunk is due then
                    }
                    out.write(c.bytes());
                    out.flush();
                }
            } catch (IOException | InterruptedException e) {
                // the other end is gone
            } finally {
                close(from);
                close(to);
            }
        });
    }

    private static void close(Socket s) {
        try {
            s.close();
        } catch (IOException e) {
            // closing anyway
        }
    }

    private static void start(String name, Runnable body) {
        Thread t = new Thread(body, name);
        t.setDaemon(true);
        t.start();
    }
}
