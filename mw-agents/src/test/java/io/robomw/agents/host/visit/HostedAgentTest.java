package io.robomw.agents.host.visit;

import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.api.Agent;
import org.junit.jupiter.api.Test;

import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CyclicBarrier;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An operator's retract or dispose and the runner beginning an agent's work at a stop: the work
 * either does not begin, or begins and is interrupted; never begins unseen by the retract (which
 * then waited for a work that may take minutes).
 */
class HostedAgentTest {

    static final class Idle extends Agent {
        private static final long serialVersionUID = 1L;

        @Override
        public void run() {
        }
    }

    private static HostedAgent arrived() {
        AgentImage image = new AgentImage(UUID.randomUUID(), 1, AgentImage.Kind.TRIP, false, "rmi://127.0.0.1:1/home", null, 0, new byte[0]);
        return new HostedAgent(image, new Idle(), HostedAgentTest.class.getClassLoader());
    }

    /** What the host does on a retract (Calls): mark it, then interrupt the work if it runs. */
    private static Thread retract(HostedAgent h) {
        h.retractRequested = true;
        return h.interruptWork();
    }

    @Test
    void aRetractAfterTheAgentArrivedAndBeforeItsWorkBeganKeepsTheWorkFromBeginning() {
        HostedAgent h = arrived();
        assertNull(retract(h), "no work runs yet: nothing to interrupt");
        assertFalse(h.working(), "the work does not begin");
    }

    @Test
    void aDisposeAfterTheAgentArrivedAndBeforeItsWorkBeganKeepsTheWorkFromBeginning() {
        HostedAgent h = arrived();
        h.disposeRequested = true;
        assertNull(h.interruptWork());
        assertFalse(h.working());
    }

    @Test
    void aRetractWhileTheWorkRunsInterruptsItsThreadAndTheInterruptEndsWithTheWork() throws Exception {
        HostedAgent h = arrived();
        assertTrue(h.working());
        assertSame(Thread.currentThread(), retract(h));
        assertTrue(Thread.currentThread().isInterrupted());
        h.rested();
        assertFalse(Thread.currentThread().isInterrupted(), "the interrupt cannot reach the runner's next agent");
    }

    /**
     * The retract and the beginning of the work raced many times: in every round exactly one of
     * them saw the other (the work did not begin, or the retract interrupted it).
     */
    @Test
    void aRetractRacingTheBeginningOfTheWorkEitherStopsItBeginningOrInterruptsIt() throws Exception {
        int rounds = 2_000;
        int stopped = 0;
        int interrupted = 0;
        for (int i = 0; i < rounds; i++) {
            HostedAgent h = arrived();
            CyclicBarrier start = new CyclicBarrier(2);
            CompletableFuture<Thread> runner = new CompletableFuture<>();
            CompletableFuture<Boolean> began = new CompletableFuture<>();
            Thread t = new Thread(() -> {
                try {
                    runner.complete(Thread.currentThread());
                    start.await(10, TimeUnit.SECONDS);
                    boolean b = h.working();
                    began.complete(b);
                    if (b) {
                        // the work: runs until the retract's interrupt comes (or 10 s, a failure below)
                        long until = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
                        while (!Thread.currentThread().isInterrupted() && System.nanoTime() < until) {
                            Thread.onSpinWait();
                        }
                        h.rested();
                    }
                } catch (Exception e) {
                    began.completeExceptionally(e);
                }
            }, "runner-" + i);
            t.start();
            start.await(10, TimeUnit.SECONDS);
            Thread interruptedThread = retract(h);
            boolean workBegan = began.get(10, TimeUnit.SECONDS);
            t.join(TimeUnit.SECONDS.toMillis(15));
            assertFalse(t.isAlive(), "round " + i + ": the work ended");
            if (workBegan) {
                assertSame(runner.get(), interruptedThread, "round " + i + ": the work began, so the retract interrupted it");
                interrupted++;
            } else {
                assertNull(interruptedThread, "round " + i + ": the work did not begin, nothing to interrupt");
                stopped++;
            }
        }
        assertEquals(rounds, stopped + interrupted);
    }
}
