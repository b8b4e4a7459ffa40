package io.robomw.it;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.Consumer;

/**
 * Runs a test's independent slow steps at once (host JVMs started, each host's figures taken by a
 * jcmd JVM), each on a named thread of its own, and waits for all of them within one deadline.
 */
public final class AtOnce {

    /**
     * One step.
     *
     * @param name what it does, for the error, for example {@code "starting host a"}
     * @param work the step
     * @param <T>  what it makes
     */
    public record Step<T>(String name, Callable<T> work) {
    }

    private AtOnce() {
    }

    /**
     * Runs every step at once and waits for them, in order, all within {@code within}.
     *
     * @param steps  the steps
     * @param within the deadline for all of them (they run at once: each step's own)
     * @param done   told of each step's result, in the steps' order, also when another step failed
     *               (so that what was started can be stopped)
     * @param <T>    what the steps make
     * @return the results, in the steps' order
     * @throws IOException naming the step that failed (its own IOException as it was), did not end in time, or
     *                     was interrupted; the first step's failure if several failed
     * @throws Error       a step's own Error (an assertion with what a process printed) as it was
     */
    public static <T> List<T> all(List<Step<T>> steps, Duration within, Consumer<? super T> done) throws IOException {
        ExecutorService threads = Executors.newFixedThreadPool(steps.size(), r -> new Thread(r, "it-at-once"));
        try {
            List<Future<T>> running = new ArrayList<>();
            for (Step<T> s : steps) {
                running.add(threads.submit(s.work()));
            }
            long deadline = System.nanoTime() + within.toNanos();
            List<T> results = new ArrayList<>();
            Throwable failed = null;
            for (int i = 0; i < steps.size(); i++) {
                String name = steps.get(i).name();
                try {
                    T t = running.get(i).get(Math.max(0, deadline - System.nanoTime()), TimeUnit.NANOSECONDS);
                    done.accept(t);
                    results.add(t);
                } catch (ExecutionException e) {
                    Throwable cause = e.getCause();
                    failed = failed != null ? failed : cause instanceof IOException || cause instanceof Error ? cause
                            : new IOException(name + " failed: " + cause, cause);
                } catch (TimeoutException e) {
                    failed = failed != null ? failed : new IOException(name + " did not end within " + within, e);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    throw new IOException("interrupted while " + name, e);
                }
            }
            if (failed instanceof Error err) {
                throw err;
            }
            if (failed != null) {
                throw (IOException) failed;
            }
            return results;
        } finally {
            threads.shutdownNow();
        }
    }
}
