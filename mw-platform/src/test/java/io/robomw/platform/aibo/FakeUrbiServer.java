package io.robomw.platform.aibo;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.util.List;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.function.Function;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * A scripted URBI server on loopback for the driver's unit tests: it greets each client, records
 * every line, and answers each line with what the test's responder returns (server lines without
 * the timestamp header, e.g. {@code "c3] *** end"} is written as {@code [00000001:c3] *** end}).
 * One client at a time; {@link #dropClient()} cuts the current one.
 */
final class FakeUrbiServer implements AutoCloseable {

    /** A command line: tag, flags, body. */
    static final Pattern COMMAND = Pattern.compile("(\\w+)(\\+end)?: (.*)[,;]");

    private final ServerSocket server;
    private final BlockingQueue<String> lines = new LinkedBlockingQueue<>();
    private final List<Socket> clients = new CopyOnWriteArrayList<>();
    private final Thread thread;
    private volatile Function<String, List<String>> responder;
    private volatile Socket current;
    private long time;

    /**
     * @param responder the answer to each line: {@code tag] payload} or {@code ] payload} (untagged) strings
     * @throws IOException if it cannot listen
     */
    FakeUrbiServer(Function<String, List<String>> responder) throws IOException {
        this.responder = responder;
        this.server = new ServerSocket(0, 4, InetAddress.getLoopbackAddress());
        this.thread = new Thread(this::serve, "fake-urbi-server");
        thread.setDaemon(true);
        thread.start();
    }

    /** @return the port */
    int port() {
        return server.getLocalPort();
    }

    /** @param r the new responder */
    void responder(Function<String, List<String>> r) {
        this.responder = r;
    }

    /**
     * @param timeoutMillis how long to wait
     * @return the next line a client sent, or {@code null}
     * @throws InterruptedException if interrupted
     */
    String nextLine(long timeoutMillis) throws InterruptedException {
        return lines.poll(timeoutMillis, TimeUnit.MILLISECONDS);
    }

    /**
     * Waits for a line matching a pattern, skipping the others.
     *
     * @param regex         the pattern
     * @param timeoutMillis how long to wait in all
     * @return the match, or {@code null}
     * @throws InterruptedException if interrupted
     */
    Matcher awaitLine(String regex, long timeoutMillis) throws InterruptedException {
        long end = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(timeoutMillis);
        Pattern p = Pattern.compile(regex);
        while (true) {
            long left = end - System.nanoTime();
            String line = left <= 0 ? null : lines.poll(left, TimeUnit.NANOSECONDS);
            if (line == null) {
                return null;
            }
            Matcher m = p.matcher(line);
            if (m.matches()) {
                return m;
            }
        }
    }

    /**
     * Sends server lines to the current client.
     *
     * @param answers {@code tag] payload} strings
     * @throws IOException if it cannot write
     */
    synchronized void send(String... answers) throws IOException {
        Socket s = current;
        if (s == null) {
            throw new IOException("no client");
        }
        OutputStream out = s.getOutputStream();
        for (String a : answers) {
            time++;
            String tagAndPayload = a.startsWith("]") ? "]" + a.substring(1) : ":" + a;
            out.write(String.format("[%08d%s\n", time, tagAndPayload).getBytes(StandardCharsets.ISO_8859_1));
        }
        out.flush();
    }

    /** Cuts the current client's connection (the robot's link is killed). */
    void dropClient() throws IOException {
        Socket s = current;
        if (s != null) {
            s.close();
        }
    }

    private void serve() {
        while (!server.isClosed()) {
            try (Socket s = server.accept()) {
                clients.add(s);
                current = s;
                send("] *** URBI fake server for tests");
                BufferedReader in = new BufferedReader(new InputStreamReader(s.getInputStream(), StandardCharsets.ISO_8859_1));
                String line;
                while ((line = in.readLine()) != null) {
                    lines.add(line);
                    List<String> answers = responder.apply(line);
                    if (!answers.isEmpty()) {
                        send(answers.toArray(String[]::new));
                    }
                }
            } catch (IOException e) {
                // the client left or the server closed; take the next
            }
        }
    }

    @Override
    public void close() throws IOException {
        server.close();
        for (Socket s : clients) {
            s.close();
        }
        try {
            thread.join(2000);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /**
     * A responder that ends every {@code +end} command at once and answers reads with a value.
     *
     * @param value what reads answer
     * @return the responder
     */
    static Function<String, List<String>> endsEverything(String value) {
        return line -> {
            Matcher m = COMMAND.matcher(line);
            if (!m.matches()) {
                return List.of();
            }
            if (m.group(2) != null) {
                return List.of(m.group(1) + "] *** end");
            }
            if (m.group(1).startsWith("r")) {
                return List.of(m.group(1) + "] " + value);
            }
            return List.of();
        };
    }
}
