package io.robomw.platform.motor;

import io.robomw.api.ManualClock;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.platform.exec.ExecutionActionThread;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Motors started in one cycle reach the link side in one batch, whatever the timing between the
 * execution action thread publishing them and the link thread taking them: a batch split in two
 * would start one wheel a round trip before the other on a slow link, and the robot would veer.
 */
class BatchHandOverTest {

    /** Hand-overs the test wants to see before it trusts that none splits a cycle. */
    private static final int MIN_BATCHES = 1_000;

    /** Records whether a batch ever carried one wheel without the other. */
    static final class PairedMotors implements MotorDriver {
        final AtomicInteger batches = new AtomicInteger();
        final AtomicReference<String> split = new AtomicReference<>();

        @Override
        public LinkTiming timing() {
            return LinkTiming.NONE;
        }

        @Override
        public int poll(FeedbackSink feedback) {
            return 0;
        }

        @Override
        public void send(List<MotorState> motors, FeedbackSink feedback) {
            batches.incrementAndGet();
            if (motors.size() != 2) {
                split.compareAndSet(null, "a batch of " + motors);
            } else if (motors.get(0).degreesPerSecond() != motors.get(1).degreesPerSecond()) {
                split.compareAndSet(null, "a batch mixing two cycles: " + motors);
            }
        }

    }

    @Test
    void shouldHandBothWheelsOfACycleToTheLinkSideTogether() throws Exception {
        PairedMotors driver = new PairedMotors();
        ManualClock clock = new ManualClock();
        MotorPlatform motors = new MotorPlatform("paired", clock, List.of("B", "C"), Duration.ofMillis(10), driver);
        ExecutionActionThread action = new ExecutionActionThread("paired", clock, Duration.ofMillis(10));
        action.addCycleListener(motors::flushOutputs);
        AtomicBoolean running = new AtomicBoolean(true);
        Thread link = new Thread(() -> {
            while (running.get()) {
                try {
                    motors.linkSide().service();
                } catch (java.io.IOException e) {
                    throw new IllegalStateException(e);
                }
            }
        }, "link-under-test");
        link.start();
        try {
            // At least 50,000 cycles, and on until the link side has taken 1,000 batches: on a busy
            // machine the link thread may get the processor seldom while this one cycles, and it is
            // the hand-overs that happen, not the cycles run, that can show a split batch.
            long deadline = System.nanoTime() + Duration.ofSeconds(60).toNanos();
            for (int i = 1; (i <= 50_000 || driver.batches.get() < MIN_BATCHES) && driver.split.get() == null
                    && System.nanoTime() < deadline; i++) {
                action.submit(motors.container(MotorCommand.of("drive", List.of(MotorTarget.run("B", i), MotorTarget.run("C", i)))));
                action.cycle();
                clock.advanceNanos(10_000_000L);
            }
        } finally {
            running.set(false);
            link.join(5000);
        }
        assertEquals(null, driver.split.get(), "every batch carried both wheels of one cycle");
        assertTrue(driver.batches.get() >= MIN_BATCHES, "the link side took many batches within a minute: " + driver.batches.get());
    }
}
