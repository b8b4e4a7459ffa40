package io.robomw.agents.messaging.robot;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.api.Agency;
import io.robomw.api.Capability;
import io.robomw.api.Messaging;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.Robots;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The verbs' contracts across the link: a robot served on a real TCP messaging node (a hand-made
 * one whose commands end only when the test says, or when they are cancelled), driven through
 * {@code Robots.remote}.
 */
class RemoteRobotContractsTest {

    private static final Duration WAIT = Duration.ofSeconds(10);

    private final io.robomw.agents.HeldRobot served = new io.robomw.agents.HeldRobot();
    private MessagingNode server;
    private Robot remote;

    @BeforeEach
    void serve() {
        server = MessagingNode.builder("host").settings(RobotProtocol.forServer(MessagingSettings.defaults())).bind("tcp://127.0.0.1:0").build();
        RobotServer.serveInsecure(server, served);
        remote = Robots.remote(server.address("tcp") + "/held");
    }

    @AfterEach
    void close() {
        remote.close();
        server.close();
    }

    @Test
    void anInterruptedRemoteMoveEndsItsCommandOnTheServingHost() throws Exception {
        AtomicReference<Throwable> thrown = new AtomicReference<>();
        Thread caller = new Thread(() -> {
            try {
                remote.move(1.0, 0.1);
            } catch (Throwable t) {
                thrown.set(t);
            }
        }, "remote-move-caller");
        caller.start();
        Await.until("the served robot is moving", WAIT, () -> served.moves.size() == 1);
        caller.interrupt();
        caller.join(WAIT.toMillis());
        assertFalse(caller.isAlive(), "the interrupted caller returned");
        assertInstanceOf(RobotException.class, thrown.get());
        assertTrue(thrown.get().getMessage().contains("interrupted while waiting for move(1.000, 0.100)"), thrown.get().getMessage());

        Await.until("the command is cancelled on the serving host", WAIT, () -> served.moves.get(0).isCancelled());
    }

    @Test
    void cancellingTheFutureOfARemoteMotionEndsItsCommandThereAndNoOther() {
        CompletableFuture<Void> turn = remote.turnAsync(Math.PI, 0.5);
        CompletableFuture<Void> move = remote.moveAsync(1.0, 0.1);
        Await.until("the served robot turns and moves", WAIT, () -> served.turns.size() == 1 && served.moves.size() == 1);
        assertTrue(move.cancel(true));

        Await.until("the move is cancelled on the serving host", WAIT, () -> served.moves.get(0).isCancelled());
        assertFalse(served.turns.get(0).isDone(), "the turn goes on");
        served.turns.get(0).complete(null);
        assertEquals(null, turn.join(), "and ends as it would have");
    }

    @Test
    void stopReturnsOnlyOnceTheServingRobotsStopHasReturned() throws Exception {
        served.holdStops();
        CompletableFuture<Void> stop = CompletableFuture.runAsync(remote::stop, r -> new Thread(r, "remote-stop-caller").start());
        assertTrue(served.stopEntered.await(WAIT.toMillis(), TimeUnit.MILLISECONDS), "the serving robot's stop() was called");
        assertFalse(stop.isDone(), "the remote stop() waits while the serving robot's stop() has not returned");
        served.releaseStops();
        stop.get(WAIT.toMillis(), TimeUnit.MILLISECONDS);
        assertEquals(1, served.stops.get());
    }

    @Test
    void aStopTheServingRobotCouldNotHandToItsHardwareFailsAsALinkErrorNamingTheRobot() {
        served.failStops();
        RobotLinkException e = assertThrows(RobotLinkException.class, remote::stop);
        assertTrue(e.getMessage().contains("robot 'held'"), e.getMessage());
    }

    @Test
    void aRobotTheHostDoesNotServeIsSaidSoNamingTheRobotsItServes() {
        io.robomw.api.RobotLinkException e = org.junit.jupiter.api.Assertions.assertThrows(io.robomw.api.RobotLinkException.class,
                () -> Robots.remote(server.address("tcp") + "/nxt-1"));
        org.junit.jupiter.api.Assertions.assertEquals("no robot 'nxt-1' is served at " + server.address("tcp") + "; it serves held ("
                + server.address("tcp") + "/held)", e.getMessage());
    }
}
