package io.robomw.agents.host.core;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A host's runner threads: they spin for the next agent only while few agents run there. */
class HostRunnersTest {

    /** A spin far longer than a host's (at most 10 ms): a runner that spins is seen spinning. */
    private final HostState host = new HostState(null, "runners", null, null, 1000, Duration.ofSeconds(3), FailurePolicy.logging());
    private final CountDownLatch release = new CountDownLatch(1);

    @AfterEach
    void close() throws InterruptedException {
        release.countDown();
        host.runners.shutdown();
        assertTrue(host.runners.awaitTermination(10, TimeUnit.SECONDS), "the runners end");
    }

    @Test
    void withMoreAgentsRunningThanProcessorsAnIdleRunnerParksAtOnceAndSpinsAgainWhenFewRun() throws Exception {
        int processors = Runtime.getRuntime().availableProcessors();
        assertTrue(host.fewAgentsRunning(), "none run yet");
        CountDownLatch started = new CountDownLatch(processors + 1);
        for (int i = 0; i <= processors; i++) {
            host.runners.execute(() -> {
                started.countDown();
                try {
                    release.await(30, TimeUnit.SECONDS); // an agent's stop that waits (for a robot's move, say)
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            });
        }
        assertTrue(started.await(10, TimeUnit.SECONDS));
        assertFalse(host.fewAgentsRunning(), (processors + 1) + " agents run on " + processors + " processors");
        // a short task's runner becomes idle while the others still run: it parks without spinning
        CountDownLatch shortDone = new CountDownLatch(1);
        host.runners.execute(shortDone::countDown);
        assertTrue(shortDone.await(10, TimeUnit.SECONDS));
        Await.until("the short task's runner parks at once (one that spun would for 3 s)", Duration.ofSeconds(2),
                () -> !hasRunnerIn(Thread.State.RUNNABLE));
        assertEquals(0, host.runnerHandoff.spinning(), "no runner spins while more agents run than there are processors");

        release.countDown();
        Await.until("the agents' stops end", Duration.ofSeconds(10), host::fewAgentsRunning);
        CountDownLatch again = new CountDownLatch(1);
        host.runners.execute(again::countDown);
        assertTrue(again.await(10, TimeUnit.SECONDS));
        Await.until("with few agents running, an idle runner spins for the next",
                Duration.ofSeconds(10), () -> {
                    if (host.runnerHandoff.spinning() > 0) {
                        return true;
                    }
                    host.runners.execute(() -> { });
                    return false;
                });
    }

    /** @return whether a runner thread of this host is in the state (a spinning one yields, so it is RUNNABLE) */
    private static boolean hasRunnerIn(Thread.State state) {
        return Thread.getAllStackTraces().keySet().stream()
                .anyMatch(t -> t.getName().startsWith("agent-runner-runners") && t.getState() == state);
    }
}
