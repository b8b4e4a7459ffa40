package io.robomw.sim.emulator.aibo;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.sim.SimRobot;
import io.robomw.sim.emulator.EmulatorStack;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.io.TempDir;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertAll;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The whole stack on four legs: the example Aibo robot file, opened by {@code Robots.open} on the
 * real {@code platform: aibo} driver, over TCP to the Aibo emulator, whose URBI server walks a
 * simulated quadruped in a dyn4j world running in real time. Every check is on the simulated dog's
 * true pose or on what the program reads back.
 *
 * <h2>Tolerances, from the gait model of the robot file</h2>
 * The feet slip 2 % ({@code gait.slip}), and each step of the gait (2.5 a second) goes
 * {@code 1 + 0.03·N(0, 1)} times as fast ({@code gait.jitter}). A walk of 0.5 m at 0.1 m/s takes
 * 5 s, 12.5 steps: it covers {@code 0.5 × 0.98 = 0.49 m}, give or take
 * {@code σ = 0.03 × 0.5 / √12.5 ≈ 4.2 mm}; plus at most one physics step (10 ms) of the commanded
 * speed (1 mm) at each end. Three σ and the two steps: ±15 mm. A quarter turn at 1 rad/s takes
 * 1.57 s, about four steps: {@code 0.98 × π/2 = 1.539 rad}, σ = 0.03 × 1.57 / 2 ≈ 0.024 rad; three
 * σ and two steps of turn (0.02 rad): ±0.09 rad.
 */
class AiboFullStackTest {

    /** The example robot file, its connection block made a template and one broken action added. */
    static String robotTemplate() throws IOException {
        String file = Files.readString(Path.of("../examples/robots/aibo.yaml")).replace("%", "%%");
        int start = file.indexOf("connection:\n");
        int end = file.indexOf("cycle_hz:");
        return file.substring(0, start)
                + "connection: { %s, reply_timeout_ms: 2000, startup: \"motoron; robot.watchdogInterval = 0.5\" }\n"
                + file.substring(end)
                + "  bad.sit: { command: \"robot.sitt()\", duration: 1.0, uses: [legs] }\n";
    }

    @TempDir
    Path dir;

    private EmulatorStack<AiboEmulator> stack;

    @AfterEach
    void close() {
        if (stack != null) {
            stack.close();
        }
    }

    private Robot open(double width, double x, double speed) throws IOException {
        stack = new EmulatorStack<>(dir, robotTemplate(), "aibo", AiboEmulator::bind);
        stack.openOnTcp(width, x, speed);
        return stack.robot();
    }

    private SimRobot dog() {
        return stack.sim().world().robot("aibo");
    }

    @Test
    void shouldWalkHalfAMetreWithinTheGaitsTolerance() throws IOException {
        Robot robot = open(3, 1.0, 4);
        Pose start = stack.truePose();

        robot.move(0.5, 0.1);

        Pose end = stack.truePose();
        assertAll(
                () -> assertEquals(0.49, end.x() - start.x(), 0.015, "walked " + (end.x() - start.x()) + " m"),
                () -> assertEquals(0, end.y() - start.y(), 0.01, "straight"),
                () -> assertEquals(0.5, robot.pose().x(), 1e-6, "its own pose: the commanded walk, whole"));
    }

    @Test
    void shouldTurnAQuarterTurnWithinTheGaitsTolerance() throws IOException {
        Robot robot = open(3, 1.0, 4);
        Pose start = stack.truePose();

        robot.turn(Math.PI / 2, 1.0);

        double turned = Pose.normalize(stack.truePose().heading() - start.heading());
        assertEquals(0.98 * Math.PI / 2, turned, 0.09, "turned " + turned + " rad");
        assertEquals(0, stack.truePose().distanceTo(start), 0.01, "on the spot");
    }

    @Test
    void shouldSeeTheWallWithTheHeadAndTurnItsRayWithTheHead() throws IOException {
        Robot robot = open(2.2, 1.0, 2);
        double ahead = 2.2 - 1.0 - 0.15;

        stack.awaitTrue(() -> Math.abs(robot.getValue(Position.FRONT, SensorType.INFRARED, ReturnType.METERS) - ahead) < 0.015,
                Duration.ofSeconds(5), "the far head sensor reads the wall " + ahead + " m ahead");
        robot.perform("head.pan", Math.toRadians(30));
        // Reads answer from the streams (every 100 ms), so they catch up with the head within a few periods.
        stack.awaitTrue(() -> Math.abs(robot.getValue("head_pan", ReturnType.DEGREES) - 30) < 0.5, Duration.ofSeconds(5),
                "the head's pan joint reads 30°");
        stack.awaitTrue(() -> Math.abs(robot.getValue("head_far", ReturnType.METERS) - ahead / Math.cos(Math.toRadians(30))) < 0.015,
                Duration.ofSeconds(5), "panned 30°, it reads the wall along the slanted ray");
    }

    @Test
    void shouldFeelAWallWithTheFrontPawsOnly() throws IOException {
        Robot robot = open(2.0, 1.0, 2);

        robot.moveAsync(1.5, 0.2);
        stack.awaitTrue(() -> robot.getValue("paw_lf", ReturnType.BOOLEAN) == 1 && robot.getValue("paw_rf", ReturnType.BOOLEAN) == 1,
                Duration.ofSeconds(10), "both front paws press against the wall");

        assertAll(
                () -> assertEquals(0, robot.getValue("paw_lh", ReturnType.BOOLEAN), "a hind paw is free"),
                () -> assertEquals(2.0 - 0.15, stack.truePose().x(), 0.02, "the dog stands at the wall"));
        robot.stop();
    }

    @Test
    void shouldStopTheDogWithinTheWatchdogWhenItsLinkIsKilled() throws Exception {
        Robot robot = open(3, 0.5, 1);
        robot.drive(0.1, 0);
        stack.awaitStep(() -> dog().quadruped().walking(), Duration.ofSeconds(5), "the dog walks");
        double killedAt = stack.sim().world().time();

        stack.emulator().dropClients();

        stack.awaitStep(() -> !dog().quadruped().walking(), Duration.ofSeconds(5), "the dog stops");
        double stoppedAfter = stack.sim().world().time() - killedAt;
        assertTrue(stoppedAfter <= 0.5, "stopped " + stoppedAfter + " s after the link was killed; the watchdog is 0.5 s");
        stack.awaitTrue(() -> {
            try {
                robot.move(0.05, 0.1);
                return true;
            } catch (RobotLinkException e) {
                return false;
            }
        }, Duration.ofSeconds(10), "the driver reconnects and the dog walks again");
        assertEquals(2, stack.emulator().connectionsServed(), "one new connection");
    }

    @Test
    void shouldStopADriveWhoseRefreshStopsWithoutTheLinkClosing() throws Exception {
        open(3, 0.5, 1);
        try (Socket raw = new Socket(InetAddress.getLoopbackAddress(), port())) {
            OutputStream out = raw.getOutputStream();
            out.write("motoron; robot.watchdogInterval = 0.5; robot.drive(0.1, 0),\n".getBytes(StandardCharsets.US_ASCII));
            out.flush();
            stack.awaitStep(() -> dog().quadruped().walking(), Duration.ofSeconds(5), "the raw client's drive walks the dog");
            double silentFrom = stack.sim().world().time();

            stack.awaitStep(() -> !dog().quadruped().walking(), Duration.ofSeconds(5), "the dog's own watchdog stops it");

            double after = stack.sim().world().time() - silentFrom;
            assertTrue(after <= 0.55, "stopped " + after + " s after the last drive; robot.watchdogInterval is 0.5 s");
        }
    }

    @Test
    void shouldReportABadCommandAsAnErrorNamingItAndGoOn() throws IOException {
        Robot robot = open(3, 1.0, 4);

        RobotException e = assertThrows(RobotException.class, () -> robot.perform("bad.sit"));

        assertTrue(e.getMessage().contains("robot.sitt()") && e.getMessage().contains("!!! unknown function: robot.sitt"), e.getMessage());
        robot.perform("sit");
        assertEquals(io.robomw.sim.legged.Quadruped.Posture.SIT, dog().quadruped().posture());
    }

    @Test
    void shouldAnswerGarbageWithErrorsAndKeepServing() throws Exception {
        open(3, 1.0, 2);
        try (Socket raw = new Socket(InetAddress.getLoopbackAddress(), port())) {
            BufferedReader in = new BufferedReader(new InputStreamReader(raw.getInputStream(), StandardCharsets.UTF_8));
            OutputStream out = raw.getOutputStream();
            out.write(("this is not urbi;\n"
                    + "x1: distanceNear.val = 3;\n"
                    + "x2: robot.walk(5, 9);\n"
                    + "x3: };\n").getBytes(StandardCharsets.US_ASCII));
            out.write(new byte[] {(byte) 0xFF, 0, 7, ';', '\n'});
            out.write("x4: ping;\nx5: headPan.val;\n".getBytes(StandardCharsets.US_ASCII));
            out.flush();

            StringBuilder seen = new StringBuilder();
            String line;
            while ((line = in.readLine()) != null && !line.contains(":x5]")) {
                seen.append(line).append('\n');
            }
            String all = seen + String.valueOf(line);
            assertAll(
                    () -> assertTrue(all.contains("] !!! syntax error"), all),
                    () -> assertTrue(all.contains(":x1] !!! distanceNear.val is a sensor; it cannot be assigned"), all),
                    () -> assertTrue(all.contains(":x2] !!! robot.walk: the speed 9.000 m/s is above the gait's 0.200 m/s"), all),
                    () -> assertTrue(all.contains("] !!! syntax error: '}' closes nothing"), all),
                    () -> assertTrue(all.contains(":x4] *** pong time="), all),
                    () -> assertTrue(all.matches("(?s).*\\[\\d{8}:x5] 0\\.000000.*"), all));
        }
    }

    /**
     * The URBI kernel's emergency escape, over the emulator's socket: a statement held open by an
     * unclosed brace takes in everything the client sends after it, until the client sends
     * {@code $$}, which abandons it; the connection then goes on as before. (The kernel also drops
     * what it received in the same read after the {@code $$}, so the client here sends on only
     * once the emulator has read it.)
     */
    @Test
    void shouldAbandonAStatementHeldOpenByABraceAtTheEmergencyEscapeAndGoOn() throws Exception {
        stack = new EmulatorStack<>(dir, robotTemplate(), "aibo", AiboEmulator::bind);
        stack.world(3, 1.0);
        AiboEmulator emulator = stack.newEmulator();
        int port = emulator.startOnTcp("127.0.0.1", 0);
        stack.sim().startRealTime(2);
        Pose start = stack.truePose();
        try (Socket raw = new Socket(InetAddress.getLoopbackAddress(), port)) {
            raw.setSoTimeout(10_000);
            BufferedReader in = new BufferedReader(new InputStreamReader(raw.getInputStream(), StandardCharsets.UTF_8));
            OutputStream out = raw.getOutputStream();
            long sent = 0;
            for (String chunk : new String[]{"motoron; h1: { robot.walk(0.3, 0.1);\n", "x1: ping;\n", "$$\n"}) {
                byte[] bytes = chunk.getBytes(StandardCharsets.US_ASCII);
                out.write(bytes);
                out.flush();
                sent += bytes.length;
                long expected = sent;
                Await.until("the emulator read '" + chunk.strip() + "'", Duration.ofSeconds(10), () -> emulator.bytesReceived() == expected);
            }
            stack.awaitHalfASimulatedSecond();

            out.write("x2: ping;\nx3: headPan.val;\n".getBytes(StandardCharsets.US_ASCII));
            out.flush();

            StringBuilder seen = new StringBuilder();
            String line;
            while ((line = in.readLine()) != null && !line.contains(":x3]")) {
                seen.append(line).append('\n');
            }
            String all = seen + String.valueOf(line);
            assertAll(
                    () -> assertTrue(all.contains(":x2] *** pong time="), "the connection went on after the escape: " + all),
                    () -> assertTrue(all.matches("(?s).*\\[\\d{8}:x3] 0\\.000000.*"), all),
                    () -> assertTrue(!all.contains(":x1]") && !all.contains(":h1]") && !all.contains("!!!"),
                            "the held statement, its ping with it, was abandoned silently: " + all),
                    () -> assertTrue(!dog().quadruped().walking() && stack.truePose().distanceTo(start) < 0.005,
                            "the abandoned walk never ran: " + stack.truePose()));
        }
    }

    private int port() {
        String d = stack.emulator().describe();
        return Integer.parseInt(d.substring(d.lastIndexOf(':') + 1));
    }
}
