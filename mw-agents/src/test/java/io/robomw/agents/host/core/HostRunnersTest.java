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

/** A host's runner threads: they spin for the next agent only while the host has had few agents at once lately. */
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
    void withFewAgentsAtOnceAnIdleRunnerSpinsForTheNext() throws Exception {
        assertTrue(host.fewAgentsLately(), "no agent yet");
        CountDownLatch ran = new CountDownLatch(1);
        host.runners.execute(ran::countDown);
        assertTrue(ran.await(10, TimeUnit.SECONDS));
        assertTrue(host.fewAgentsLately(), "one runner thread");
        Await.until("the idle runner spins for the next agent", Duration.ofSeconds(10), () -> host.runnerHandoff.spinning() == 1);
        assertTrue(host.runnerHandoff.offer(() -> { }), "the spinning runner takes the next agent at once");
    }

    @Test
    void withManyAgentsAtOnceLatelyIdleRunnersParkAtOnce() throws Exception {
        int many = 8 * Runtime.getRuntime().availableProcessors() + 1;
        CountDownLatch started = new CountDownLatch(many);
        for (int i = 0; i < many; i++) {
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
        assertFalse(host.fewAgentsLately(), many + " agents at once on " + Runtime.getRuntime().availableProcessors() + " processors");
        release.countDown();
        // their runners are idle now, and kept for the next agents: none spins (one that did would for 3 s)
        Await.until("every runner parks at once", Duration.ofSeconds(2), () -> !hasRunnerIn(Thread.State.RUNNABLE));
        assertEquals(0, host.runnerHandoff.spinning(), "no runner spins");
        assertFalse(host.fewAgentsLately(), "the host had many agents at once lately: its threads stay for " + HostState.IDLE_THREAD_SECONDS + " s");
    }

    /** @return whether a runner thread of this host is in the state (a spinning one yields, so it is RUNNABLE) */
    private static boolean hasRunnerIn(Thread.State state) {
        return Thread.getAllStackTraces().keySet().stream()
                .anyMatch(t -> t.getName().startsWith("agent-runner-runners") && t.getState() == state);
    }
}
