package io.robomw.platform.link;

import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;

/** A named daemon thread for the side of a test that must block while the test thread acts. */
final class TestThreads {

    private TestThreads() {
    }

    /** @return a single-thread executor whose thread is named {@code name} */
    static ExecutorService named(String name) {
        return Executors.newSingleThreadExecutor(r -> {
            Thread t = new Thread(r, name);
            t.setDaemon(true);
            return t;
        });
    }

    /** Stops the executor, waiting a little for a task that is ending. */
    static void stop(ExecutorService executor) throws InterruptedException {
        executor.shutdownNow();
        executor.awaitTermination(2, TimeUnit.SECONDS);
    }
}
