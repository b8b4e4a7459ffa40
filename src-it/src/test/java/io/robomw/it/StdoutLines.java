package io.robomw.it;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.util.List;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * The stdout of a process a test started, line by line, for waiting on with deadlines: a named
 * daemon thread reads it into a queue as it comes. When the stream ends (the process exited or
 * was stopped) the queue gets one last line for which {@link #ended(String)} holds.
 */
public final class StdoutLines {

    private static final String END = "\u0000EOF";

    private final BlockingQueue<String> lines = new LinkedBlockingQueue<>();
    private final List<String> all = new CopyOnWriteArrayList<>();

    /**
     * Starts reading.
     *
     * @param process    the process
     * @param threadName the reading thread's name
     */
    public StdoutLines(Process process, String threadName) {
        Thread reader = new Thread(() -> {
            try (BufferedReader r = new BufferedReader(new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8))) {
                for (String line; (line = r.readLine()) != null; ) {
                    all.add(line);
                    lines.add(line);
                }
                lines.add(END);
            } catch (IOException e) {
                lines.add(END + " (" + e + ")");
            }
        }, threadName);
        reader.setDaemon(true);
        reader.start();
    }

    /**
     * @param deadlineNanos until when to wait, on the {@link System#nanoTime()} clock
     * @return the next line, or {@code null} if none came in time
     * @throws InterruptedException if interrupted while waiting
     */
    public String next(long deadlineNanos) throws InterruptedException {
        return lines.poll(Math.max(0, deadlineNanos - System.nanoTime()), TimeUnit.NANOSECONDS);
    }

    /**
     * @param line a line {@link #next} returned
     * @return whether it says that the stream ended (no line follows it)
     */
    public static boolean ended(String line) {
        return line.startsWith(END);
    }

    /** @return every line read so far, joined by newlines */
    public String transcript() {
        return String.join("\n", all);
    }
}
