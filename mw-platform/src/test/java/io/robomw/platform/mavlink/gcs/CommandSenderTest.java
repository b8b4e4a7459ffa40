package io.robomw.platform.mavlink.gcs;

import io.robomw.api.RobotException;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavResult;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.Payload;
import org.junit.jupiter.api.Test;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** COMMAND_ACK matching and retries as MAVSDK does them, on a manual clock. */
class CommandSenderTest {

    private static final long MS = 1_000_000L;
    private final List<Payload> sent = new ArrayList<>();
    private final CommandSender sender = new CommandSender("copter", sent::add, 255, 190);

    private static Payload ack(MavCmd command, MavResult result, int targetSystem, int targetComponent) {
        return Payload.of(Messages.CommandAck.MESSAGE).set(Messages.CommandAck.COMMAND, command.code()).set(Messages.CommandAck.RESULT, result.code())
                .set(Messages.CommandAck.TARGET_SYSTEM, targetSystem).set(Messages.CommandAck.TARGET_COMPONENT, targetComponent);
    }

    @Test
    void anUnansweredCommandIsSentFourTimesThenFailsAfterTwoSeconds() {
        CompletableFuture<Void> f = sender.send(1, 1, MavCmd.COMPONENT_ARM_DISARM, 0, 1);
        for (long t = 0; t <= 2100; t += 50) {
            sender.tick(t * MS);
        }
        assertEquals(4, sent.size(), "the first and three retries");
        ExecutionException e = assertThrows(ExecutionException.class, f::get);
        assertTrue(e.getCause().getMessage().contains("did not answer COMPONENT_ARM_DISARM (sent 4 times, 2.0 s)"), e.getCause().getMessage());
    }

    @Test
    void anAckForAnotherGroundStationIsIgnoredAndOneForNobodyIsTaken() {
        CompletableFuture<Void> f = sender.send(1, 1, MavCmd.NAV_TAKEOFF, 0);
        sender.acknowledged(ack(MavCmd.NAV_TAKEOFF, MavResult.ACCEPTED, 245, 190), 10 * MS);
        assertFalse(f.isDone(), "addressed to MAVSDK, not to us");
        sender.acknowledged(ack(MavCmd.NAV_TAKEOFF, MavResult.ACCEPTED, 0, 0), 20 * MS);
        assertTrue(f.isDone() && !f.isCompletedExceptionally());
    }

    @Test
    void inProgressHoldsTheCommandWithoutResendingItUntilItsResult() {
        CompletableFuture<Void> f = sender.send(1, 1, MavCmd.NAV_TAKEOFF, 0);
        sender.acknowledged(ack(MavCmd.NAV_TAKEOFF, MavResult.IN_PROGRESS, 255, 190), 100 * MS);
        for (long t = 100; t <= 2900; t += 50) {
            sender.tick(t * MS);
        }
        assertEquals(1, sent.size(), "not sent again while in progress");
        assertFalse(f.isDone());
        sender.acknowledged(ack(MavCmd.NAV_TAKEOFF, MavResult.ACCEPTED, 255, 190), 3000 * MS);
        assertTrue(f.isDone() && !f.isCompletedExceptionally());
    }

    @Test
    void anyOtherResultFailsNamingIt() {
        CompletableFuture<Void> f = sender.send(1, 1, MavCmd.NAV_TAKEOFF, 0);
        sender.acknowledged(ack(MavCmd.NAV_TAKEOFF, MavResult.UNSUPPORTED, 255, 190), 10 * MS);
        ExecutionException e = assertThrows(ExecutionException.class, f::get);
        RobotException r = assertInstanceOf(RobotException.class, e.getCause());
        assertEquals("robot 'copter': the vehicle answered NAV_TAKEOFF with UNSUPPORTED", r.getMessage());
    }

    @Test
    void aNewerCommandOfTheSameIdSupersedesTheOlder() {
        CompletableFuture<Void> first = sender.send(1, 1, MavCmd.DO_SET_MODE, 0, 1, 4);
        CompletableFuture<Void> second = sender.send(1, 1, MavCmd.DO_SET_MODE, 0, 1, 9);
        assertTrue(first.isCompletedExceptionally());
        sender.acknowledged(ack(MavCmd.DO_SET_MODE, MavResult.ACCEPTED, 255, 190), 10 * MS);
        assertTrue(second.isDone() && !second.isCompletedExceptionally());
    }
}
