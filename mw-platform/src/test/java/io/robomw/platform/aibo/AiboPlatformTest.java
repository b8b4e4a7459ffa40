package io.robomw.platform.aibo;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.testkit.Await;
import io.robomw.platform.command.HighLevelRobotPlatform;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The Aibo driver against a scripted URBI server on loopback: what it sends, and what it makes of
 * the answers, the errors and a lost link. (The emulator-backed tests in mw-sim drive a simulated
 * dog with it.)
 */
class AiboPlatformTest {

    private static final long WAIT_MS = 5000;

    private final List<AutoCloseable> toClose = new ArrayList<>();

    @AfterEach
    void closeAll() throws Exception {
        for (int i = toClose.size() - 1; i >= 0; i--) {
            toClose.get(i).close();
        }
    }

    private FakeUrbiServer server(java.util.function.Function<String, List<String>> responder) throws IOException {
        FakeUrbiServer s = new FakeUrbiServer(responder);
        toClose.add(s);
        return s;
    }

    private HighLevelRobotPlatform open(FakeUrbiServer server, int streamMs, SensorChannel... sensors) throws IOException {
        PlatformConfig config = new PlatformConfig("dog", "aibo", new ConnectionSettings(Map.of("host", "127.0.0.1", "port", server.port(),
                "stream_ms", streamMs, "reply_timeout_ms", 1000), "dog.yaml"), List.of(), List.of(sensors), Duration.ofMillis(10),
                Duration.ofMillis(500), Clock.system(), PlatformServices.none(), io.robomw.api.spi.Cycling.OWN_THREADS, io.robomw.api.spi.FailurePolicy.logging());
        HighLevelRobotPlatform p = (HighLevelRobotPlatform) new AiboPlatformProvider().open(config);
        toClose.add(p);
        return p;
    }

    private static HighLevelCommand walk(String text) {
        return new HighLevelCommand("move", text, Map.of(), Set.of("legs"), Duration.ofSeconds(5), false, CommandPriority.NORMAL,
                Duration.ZERO, "robot.stop()");
    }

    private static SensorChannel sensor(String name, String device) {
        return new SensorChannel(name, SensorType.INFRARED, device, Map.of());
    }

    private static Throwable failure(CompletableFuture<?> f) {
        return assertThrows(ExecutionException.class, () -> f.get(WAIT_MS, TimeUnit.MILLISECONDS)).getCause();
    }

    @Test
    void shouldSwitchTheMotorsOnAndRunAWalkUntilItsEnd() throws Exception {
        FakeUrbiServer server = server(FakeUrbiServer.endsEverything("0"));
        HighLevelRobotPlatform dog = open(server, 0);
        assertNotNull(server.awaitLine("o\\d+\\+end: \\{ motoron \\},", WAIT_MS), "the startup command");

        server.responder(line -> List.of());
        CompletableFuture<Void> done = dog.execute(walk("robot.walk(0.5, 0.1)"));
        Matcher walk = server.awaitLine("(c\\d+)\\+end: \\{ robot\\.walk\\(0\\.5, 0\\.1\\) \\},", WAIT_MS);
        assertNotNull(walk, "the walk as a tagged block");
        server.send(walk.group(1) + "] *** end");

        done.get(WAIT_MS, TimeUnit.MILLISECONDS);
    }

    @Test
    void shouldFailACommandTheRobotAnswersWithAnErrorNamingTheCommandAndTheError() throws Exception {
        FakeUrbiServer server = server(FakeUrbiServer.endsEverything("0"));
        HighLevelRobotPlatform dog = open(server, 0);
        server.responder(line -> {
            Matcher m = FakeUrbiServer.COMMAND.matcher(line);
            return m.matches() ? List.of(m.group(1) + "] !!! unknown identifier: robot.wlak", m.group(1) + "] *** end") : List.of();
        });

        Throwable e = failure(dog.execute(walk("robot.wlak(0.5, 0.1)")));

        assertInstanceOf(RobotException.class, e);
        assertTrue(e.getMessage().contains("robot.wlak(0.5, 0.1)") && e.getMessage().contains("!!! unknown identifier: robot.wlak"), e.getMessage());
    }

    @Test
    void shouldRefuseToOpenOnAServerThatNeverEndsTheStartup() throws Exception {
        FakeUrbiServer server = server(line -> List.of());

        IOException e = assertThrows(IOException.class, () -> open(server, 0));

        assertTrue(e.getMessage().contains("did not end the startup command 'motoron'"), e.getMessage());
    }

    @Test
    void shouldReadADeviceOnDemandAndTurnAnErrorIntoOneNamingTheDevice() throws Exception {
        FakeUrbiServer server = server(FakeUrbiServer.endsEverything("421.000000"));
        HighLevelRobotPlatform dog = open(server, 0, sensor("near", "distanceNear"), sensor("tail", "tialPan"));

        assertEquals(421.0, dog.readRaw("near").get(WAIT_MS, TimeUnit.MILLISECONDS));
        assertNotNull(server.awaitLine("r\\d+: distanceNear\\.val,", WAIT_MS));

        server.responder(line -> {
            Matcher m = FakeUrbiServer.COMMAND.matcher(line);
            return m.matches() ? List.of(m.group(1) + "] !!! unknown identifier: tialPan.val") : List.of();
        });
        Throwable e = failure(dog.readRaw("tail"));
        assertTrue(e.getMessage().contains("'tail' (tialPan.val)") && e.getMessage().contains("unknown identifier"), e.getMessage());
    }

    @Test
    void shouldAnswerReadsFromTheStreamWithoutAskingTheRobot() throws Exception {
        FakeUrbiServer server = server(FakeUrbiServer.endsEverything("0"));
        HighLevelRobotPlatform dog = open(server, 1000, sensor("far", "distanceFar"));
        Matcher stream = server.awaitLine("(s\\d+): every\\(1000ms\\) distanceFar\\.val,", WAIT_MS);
        assertNotNull(stream, "the sensor is streamed");
        server.responder(line -> List.of(line.startsWith("r") ? line.substring(0, line.indexOf(':')) + "] 9999" : "] ignored"));

        server.send(stream.group(1) + "] 640.000000");
        Await.until("the streamed value arrives", Duration.ofSeconds(5), () -> dog.readRaw("far").join() == 640.0);

        assertEquals(640.0, dog.readRaw("far").get(WAIT_MS, TimeUnit.MILLISECONDS));
    }

    @Test
    void shouldEndCommandsWhenTheLinkIsKilledAndReconnectWithTheStartupAndStreams() throws Exception {
        FakeUrbiServer server = server(line -> line.startsWith("o") ? FakeUrbiServer.endsEverything("0").apply(line) : List.of());
        HighLevelRobotPlatform dog = open(server, 100, sensor("far", "distanceFar"));
        CompletableFuture<Void> walking = dog.execute(walk("robot.walk(2, 0.1)"));
        assertNotNull(server.awaitLine("c\\d+\\+end: .*", WAIT_MS));

        server.dropClient();

        assertInstanceOf(RobotLinkException.class, failure(walking));
        assertNotNull(server.awaitLine("o\\d+\\+end: \\{ motoron \\},", WAIT_MS), "the startup is sent again on the new connection");
        assertNotNull(server.awaitLine("s\\d+: every\\(100ms\\) distanceFar\\.val,", WAIT_MS), "and the streams");
        Await.until("the link is restored", Duration.ofSeconds(5), () -> !dog.isLinkDown());
        server.responder(FakeUrbiServer.endsEverything("0"));
        dog.execute(walk("robot.walk(0.1, 0.1)")).get(WAIT_MS, TimeUnit.MILLISECONDS);
    }

    @Test
    void shouldStopARunningWalkOnTheRobotWhenClosed() throws Exception {
        FakeUrbiServer server = server(line -> line.startsWith("o") ? FakeUrbiServer.endsEverything("0").apply(line) : List.of());
        HighLevelRobotPlatform dog = open(server, 0);
        dog.execute(walk("robot.walk(2, 0.1)"));
        Matcher walk = server.awaitLine("(c\\d+)\\+end: .*", WAIT_MS);
        assertNotNull(walk);

        dog.close();

        assertNotNull(server.awaitLine("stop " + walk.group(1) + ",", WAIT_MS), "the walk is stopped by its tag");
        assertNotNull(server.awaitLine("x\\d+\\+end: \\{ robot\\.stop\\(\\) \\},", WAIT_MS), "then the robot is told to stand");
    }

    @Test
    void stopAllCompletesOnceTheWalksStopIsWrittenAndAWalkAfterItIsAdmitted() throws Exception {
        FakeUrbiServer server = server(line -> line.startsWith("o") ? FakeUrbiServer.endsEverything("0").apply(line) : List.of());
        HighLevelRobotPlatform dog = open(server, 0);
        CompletableFuture<Void> walking = dog.execute(walk("robot.walk(2, 0.1)"));
        Matcher walk = server.awaitLine("(c\\d+)\\+end: .*", WAIT_MS);
        assertNotNull(walk);

        dog.stopAll().get(WAIT_MS, TimeUnit.MILLISECONDS);

        assertInstanceOf(io.robomw.api.CommandPreemptedException.class, failure(walking));
        assertNotNull(server.awaitLine("stop " + walk.group(1) + ",", WAIT_MS), "the walk's stop was written");
        dog.execute(walk("robot.walk(0.5, 0.1)"));
        assertNotNull(server.awaitLine("c\\d+\\+end: \\{ robot\\.walk\\(0\\.5, 0\\.1\\) \\},", WAIT_MS), "the walk after the stop is sent, not held by 'stop'");
    }
}
