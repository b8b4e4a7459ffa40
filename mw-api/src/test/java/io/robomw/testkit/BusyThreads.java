package io.robomw.testkit;

import java.util.ArrayList;
import java.util.List;

/**
 * Threads that keep the machine's cores busy while a test runs, as a loaded host would: each
 * spins on arithmetic until closed. Two of them on a two-core machine leave the driver's link
 * thread, the emulator and the simulation to compete for time with them, so a driver that only
 * works on an idle machine fails.
 */
public final class BusyThreads implements AutoCloseable {

    private final List<Thread> threads = new ArrayList<>();
    private volatile boolean running = true;
    private volatile long sink;

    /**
     * Starts the threads.
     *
     * @param count how many
     */
    public BusyThreads(int count) {
        for (int i = 0; i < count; i++) {
            Thread t = new Thread(this::spin, "busy-" + i);
            t.setDaemon(true);
            threads.add(t);
            t.start();
        }
    }

    private void spin() {
        long x = 1;
        while (running) {
            for (int i = 0; i < 10_000; i++) {
                x = x * 6364136223846793005L + 1442695040888963407L;
            }
            sink = x;
        }
    }

    /** Stops the threads and waits for them. */
    @Override
    public void close() {
        running = false;
        for (Thread t : threads) {
            try {
                t.join(2000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }
}
