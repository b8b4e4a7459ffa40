package io.robomw.platform.motor;

import io.robomw.api.ManualClock;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.platform.exec.ExecutionActionThread;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;

/**
 * The end of a move on a brick that stops at its limit (the NXT's tacho limit), with the action
 * side and the link side turned by hand: the link side brakes the motor as soon as the brick says
 * it stopped, without waiting for the action thread, and the brake the action thread then decides
 * on is not sent a second time.
 */
class MotorLinkSideTest {

    /** A brick that ends limited rotations itself; the test says when. */
    static final class LimitBrick implements MotorDriver, LinkTiming {
        final List<List<MotorState>> sent = new ArrayList<>();
        boolean stoppedAtLimit;

        @Override
        public void send(List<MotorState> states, FeedbackSink feedback) {
            sent.add(List.copyOf(states));
        }

        @Override
        public int poll(FeedbackSink feedback) {
            if (stoppedAtLimit) {
                feedback.stoppedAtLimit("B");
            }
            return 0;
        }

        @Override
        public LinkTiming timing() {
            return this;
        }

        @Override
        public boolean stopsAtLimit() {
            return true;
        }
    }

    private final ManualClock clock = new ManualClock();
    private final LimitBrick brick = new LimitBrick();
    private final MotorPlatform motors = new MotorPlatform("limit", clock, List.of("B", "C"), Duration.ofMillis(10), brick);
    private final ExecutionActionThread action = new ExecutionActionThread("limit", clock, Duration.ofMillis(10));

    @AfterEach
    void close() {
        action.close();
    }

    private void cycle() {
        action.cycle();
        clock.advance(Duration.ofMillis(10));
    }

    @Test
    void theBrickStoppingAtItsLimitIsBrakedFromTheLinkSideOnceWithoutWaitingForTheActionThread() throws Exception {
        action.addCycleListener(() -> motors.flushOutputs(action.cycles() + 1));
        CompletableFuture<Void> move = action.submit(motors.container(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 90, 90)))));
        cycle();
        motors.linkSide().service();
        assertEquals(List.of(List.of(new MotorState("B", 90, 90, MotorState.StopMode.BRAKE))), brick.sent);

        brick.stoppedAtLimit = true;
        motors.linkSide().service(); // the poll hears that the brick stopped the motor at its limit
        motors.linkSide().service(); // the next round brakes it: no action cycle in between
        MotorState braked = MotorState.stopped("B", MotorState.StopMode.BRAKE);
        assertEquals(List.of(braked), brick.sent.get(1), "braked from the link side");
        assertFalse(move.isDone(), "the action thread has not run since");

        cycle(); // the action thread ends the move, and wants B braked
        move.get(0, TimeUnit.SECONDS);
        motors.linkSide().service();
        motors.linkSide().service();
        assertEquals(2, brick.sent.size(), "the brake the action thread decided on equals what was sent: not sent again: " + brick.sent);
    }

    @Test
    void aMoveStartedBeforeTheLinkSideBrakesGoesOutInsteadOfTheBrake() throws Exception {
        action.addCycleListener(() -> motors.flushOutputs(action.cycles() + 1));
        action.submit(motors.container(MotorCommand.of("move", List.of(MotorTarget.rotate("B", 90, 90)))));
        cycle();
        motors.linkSide().service();
        brick.stoppedAtLimit = true;
        motors.linkSide().service();
        brick.stoppedAtLimit = false;

        cycle(); // ends the first move
        action.submit(motors.container(MotorCommand.of("again", List.of(MotorTarget.rotate("B", 45, 90)))));
        cycle(); // starts the second in the batch the link side takes next
        motors.linkSide().service();
        assertEquals(List.of(new MotorState("B", 90, 45, MotorState.StopMode.BRAKE)), brick.sent.get(brick.sent.size() - 1),
                "the new rotation, not the brake, is what the brick gets");
    }
}
