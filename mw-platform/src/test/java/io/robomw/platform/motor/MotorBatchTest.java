package io.robomw.platform.motor;

import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The batch's Platform Layer keeps the execution action thread's rules for a refreshed drive,
 * member by member: a refresh reaches the motors at the member's next cycle, not before; the
 * newest refresh before a cycle wins; a drive not refreshed within the watchdog brakes; a failure
 * or a release brakes; a released member takes no more refreshes; one member never moves another.
 */
class MotorBatchTest {

    private static final long MS = 1_000_000;

    /** The motors' speeds as the driver last set them, per member. */
    private final double[][] motors = new double[3][2];
    private final List<String> sends = new ArrayList<>();
    private final MotorBatch batch = new MotorBatch("swarm-bot.yaml", List.of("B", "C"), 3, Duration.ofMillis(500), new BatchMotorDriver() {
        @Override
        public void send(int member, double[] speeds, int from) {
            motors[member][0] = speeds[from];
            motors[member][1] = speeds[from + 1];
            sends.add(member + ":" + speeds[from] + "," + speeds[from + 1]);
        }

        @Override
        public double degrees(int member, int motor) {
            return 100 * member + motor;
        }
    });

    @Test
    void aRefreshReachesTheMotorsAtTheMembersNextCycleAndTheNewestWins() {
        batch.refresh(1, 90, 120);
        assertEquals(0, motors[1][0], "nothing moves before the member's cycle");
        batch.refresh(1, 180, 240);
        batch.cycle(1, 0);
        assertEquals(List.of("1:180.0,240.0"), sends, "the newest refresh before the cycle, sent once");
        assertTrue(batch.running(1));
        assertEquals(180, batch.wanted(1, 0));
        assertFalse(batch.running(0), "another member is left alone");
        assertEquals(0, motors[0][0]);
        batch.refresh(1, 180, 240);
        batch.cycle(1, 100 * MS);
        assertEquals(1, sends.size(), "a refresh with the same speeds sends nothing");
        assertEquals(101.0, batch.degrees(1, 1), "encoders come from the driver");
    }

    @Test
    void aDriveNotRefreshedWithinItsWatchdogBrakesItsMotors() {
        batch.refresh(0, 90, 90);
        batch.cycle(0, 0);
        batch.cycle(0, 500 * MS);
        assertTrue(batch.running(0), "at the watchdog's time it still runs (it ends once it has run longer)");
        batch.refresh(0, 90, 90);
        batch.cycle(0, 600 * MS);
        batch.cycle(0, 1_000 * MS);
        assertTrue(batch.running(0), "a refresh restarted the watchdog");
        batch.cycle(0, 1_200 * MS);
        assertFalse(batch.running(0), "0.6 s without a refresh: the drive ended");
        assertEquals(0, motors[0][0]);
        assertEquals(0, motors[0][1]);
        batch.refresh(0, 45, 45);
        batch.cycle(0, 1_300 * MS);
        assertEquals(45, motors[0][0], "a later refresh starts a new drive");
    }

    @Test
    void noWatchdogMeansADriveRunsUntilReplaced() {
        MotorBatch unwatched = new MotorBatch("b", List.of("B", "C"), 1, Duration.ZERO, IDLE);
        unwatched.refresh(0, 10, 10);
        unwatched.cycle(0, 0);
        unwatched.cycle(0, 3_600_000 * MS);
        assertTrue(unwatched.running(0));
    }

    @Test
    void aFailureOrAReleaseBrakesAndAReleasedMemberTakesNoMoreRefreshes() {
        batch.refresh(2, 90, 90);
        batch.cycle(2, 0);
        batch.fail(2);
        assertFalse(batch.running(2));
        assertEquals(0, motors[2][0], "a failure brakes the member's motors");
        batch.refresh(2, 30, 30);
        batch.cycle(2, 100 * MS);
        assertEquals(30, motors[2][0], "a failed member drives again at its next refresh");
        batch.release(2);
        assertEquals(0, motors[2][0], "a release brakes");
        assertTrue(batch.released(2));
        IllegalStateException e = assertThrows(IllegalStateException.class, () -> batch.refresh(2, 1, 1));
        assertTrue(e.getMessage().contains("swarm-bot.yaml") && e.getMessage().contains("member 2"), e.getMessage());
        int sent = sends.size();
        batch.cycle(2, 200 * MS);
        batch.fail(2);
        assertEquals(sent, sends.size(), "a released member is not touched again");
    }

    @Test
    void refusesWhatDoesNotFit() {
        MotorBatch three = new MotorBatch("arm", List.of("A", "B", "C"), 1, Duration.ZERO, IDLE);
        assertThrows(IllegalArgumentException.class, () -> three.refresh(0, 1, 2), "two speeds for three motors");
        assertThrows(IllegalArgumentException.class, () -> new MotorBatch("none", List.of(), 1, Duration.ZERO, IDLE));
        assertThrows(IllegalArgumentException.class, () -> new MotorBatch("late", List.of("B"), 1, Duration.ofMillis(-1), IDLE));
    }

    /** A driver of motors nobody looks at. */
    private static final BatchMotorDriver IDLE = new BatchMotorDriver() {
        @Override
        public void send(int member, double[] speeds, int from) {
        }

        @Override
        public double degrees(int member, int motor) {
            return 0;
        }
    };
}
