package io.robomw.sim.render;

import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The viewer's pause and speed logic, without a window. Whether the simulation's real-time thread
 * runs is checked by {@link Simulation#runFor}, which it refuses while one does.
 */
class RealTimeControlTest {

    private static final Duration STEP = Duration.ofMillis(10);

    @TempDir
    Path dir;

    @Test
    void shouldStartPausedAndRunAfterResume() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RealTimeControl control = new RealTimeControl(sim, 1);
            assertFalse(control.isRunning());
            sim.runFor(STEP);
            control.resume();
            assertTrue(control.isRunning());
            assertThrows(IllegalStateException.class, () -> sim.runFor(STEP), "the real-time thread steps the world");
            control.stop();
        }
    }

    @Test
    void shouldHoldSimulatedTimeWhilePausedAndGoOnWhenResumed() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RealTimeControl control = new RealTimeControl(sim, 8);
            control.resume();
            control.togglePause();
            assertFalse(control.isRunning());
            assertTrue(sim.isPaused(), "paused, not stopped: robot calls from other threads wait instead of being refused");
            assertThrows(IllegalStateException.class, () -> sim.runFor(STEP), "the real-time thread still owns the world");
            double time = sim.world().time();
            control.togglePause();
            io.robomw.testkit.Await.until("simulated time advances after resume", Duration.ofSeconds(5), () -> sim.world().time() >= time + 0.1);
            control.stop();
            sim.runFor(STEP);
        }
    }

    @Test
    void shouldKeepRunningWhenSpeedChanges() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RealTimeControl control = new RealTimeControl(sim, 1);
            control.resume();
            assertEquals(2, control.faster());
            assertTrue(control.isRunning());
            assertThrows(IllegalStateException.class, () -> sim.runFor(STEP), "restarted at the new speed");
            control.stop();
        }
    }

    @Test
    void shouldDoubleSpeedUpToMaximum() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RealTimeControl control = new RealTimeControl(sim, 16);
            assertEquals(32, control.faster());
            assertEquals(64, control.faster());
            assertEquals(RealTimeControl.MAX_SPEED, control.faster());
        }
    }

    @Test
    void shouldHalveSpeedDownToMinimum() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RealTimeControl control = new RealTimeControl(sim, 0.25);
            assertEquals(0.125, control.slower());
            assertEquals(0.0625, control.slower());
            assertEquals(RealTimeControl.MIN_SPEED, control.slower());
        }
    }

    @Test
    void shouldNotResumeAfterStop() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RealTimeControl control = new RealTimeControl(sim, 1);
            control.resume();
            control.stop();
            control.resume();
            assertFalse(control.isRunning());
            sim.runFor(STEP);
        }
    }

    @Test
    void shouldRejectSpeedOutsideLimits() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            assertThrows(IllegalArgumentException.class, () -> new RealTimeControl(sim, 100));
            assertThrows(IllegalArgumentException.class, () -> new RealTimeControl(sim, 0));
        }
    }

    @Test
    void shouldFormatSpeedsAsFactors() {
        assertEquals("1/4×", RealTimeControl.format(0.25));
        assertEquals("1×", RealTimeControl.format(1));
        assertEquals("16×", RealTimeControl.format(16));
    }
}
