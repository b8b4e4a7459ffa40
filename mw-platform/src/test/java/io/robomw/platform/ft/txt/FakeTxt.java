package io.robomw.platform.ft.txt;

import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * A scripted TXT on 127.0.0.1 for driver tests: answers the table's requests with fixed replies,
 * the exchange with the counters and inputs the test sets, and records every request. One client
 * at a time; {@link #dropClient()} hangs up on the current one.
 */
final class FakeTxt implements AutoCloseable {

    private final ServerSocket server;
    private final Thread thread;
    private final List<byte[]> requests = new ArrayList<>();
    private final int[] counterValue = new int[TxtProtocol.COUNTERS];
    private final int[] input = new int[TxtProtocol.INPUTS];
    private volatile Socket client;

    FakeTxt() throws IOException {
        server = new ServerSocket(0, 4, InetAddress.getLoopbackAddress());
        thread = new Thread(this::serve, "fake-txt");
        thread.setDaemon(true);
        thread.start();
    }

    int port() {
        return server.getLocalPort();
    }

    synchronized void counter(int c, int value) {
        counterValue[c] = value;
    }

    synchronized void input(int i, int value) {
        input[i] = value;
    }

    /** @return the ids of every request so far, in order */
    synchronized List<Long> requestIds() {
        return requests.stream().map(TxtProtocol::messageId).toList();
    }

    /** @return the last exchange request */
    synchronized TxtProtocol.Exchange lastExchange() {
        for (int i = requests.size() - 1; i >= 0; i--) {
            if (TxtProtocol.messageId(requests.get(i)) == TxtProtocol.EXCHANGE) {
                return TxtProtocol.Exchange.decode(requests.get(i));
            }
        }
        throw new AssertionError("no exchange was sent");
    }

    /** @return the last configuration sent */
    synchronized TxtProtocol.Config lastConfig() {
        for (int i = requests.size() - 1; i >= 0; i--) {
            if (TxtProtocol.messageId(requests.get(i)) == TxtProtocol.UPDATE_CONFIG) {
                return TxtProtocol.Config.decode(requests.get(i));
            }
        }
        throw new AssertionError("no configuration was sent");
    }

    void dropClient() throws IOException {
        Socket s = client;
        if (s != null) {
            s.close();
        }
    }

    private void serve() {
        while (!server.isClosed()) {
            try (Socket s = server.accept()) {
                client = s;
                DataInputStream in = new DataInputStream(s.getInputStream());
                OutputStream out = s.getOutputStream();
                while (true) {
                    byte[] id = new byte[TxtProtocol.ID_LENGTH];
                    in.readFully(id);
                    long messageId = TxtProtocol.messageId(id);
                    byte[] request = Arrays.copyOf(id, TxtProtocol.requestLength(messageId));
                    in.readFully(request, TxtProtocol.ID_LENGTH, request.length - TxtProtocol.ID_LENGTH);
                    out.write(answer(request));
                }
            } catch (EOFException | java.net.SocketException e) {
                // the client left or we hung up: serve the next
            } catch (IOException e) {
                if (!server.isClosed()) {
                    throw new IllegalStateException(e);
                }
            }
        }
    }

    private synchronized byte[] answer(byte[] request) {
        requests.add(request);
        long id = TxtProtocol.messageId(request);
        if (id == TxtProtocol.QUERY_STATUS) {
            return new TxtProtocol.Status("FakeTXT", 0x04060600L).encode();
        } else if (id == TxtProtocol.EXCHANGE) {
            return new TxtProtocol.ExchangeReply(input, new int[4], counterValue, new int[4], new int[4], 0,
                    new byte[TxtProtocol.IR_LENGTH]).encode();
        }
        return TxtProtocol.ack(TxtProtocol.replyId(id));
    }

    @Override
    public void close() throws Exception {
        server.close();
        dropClient();
        thread.join(2000);
    }
}
