package io.robomw.it.rosbridge;

import io.robomw.testkit.Ports;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * RoboMW as ROS 2 users reach it, with the client they use: roslibpy 2.1.0 (PyPI), through both of
 * its transports (Twisted, its default, and asyncio), each in its own Python process, against
 * {@code mw sim --rosbridge} and against {@code mw rosbridge} over a robot another process serves,
 * each RoboMW in its own JVM. The script (src-it/src/test/python/roslibpy_client.py) lists the
 * topics through rosapi, subscribes to odometry and a range sensor, drives the robot with Twist on
 * cmd_vel and sees it move and then stop (its watchdog) once it stops publishing, calls a move
 * service, and is refused cleanly for bad input while its connection goes on.
 */
class RoslibpyIT {

    private static final Duration WITHIN = Duration.ofSeconds(60);
    private static final Duration SCRIPT = Duration.ofMinutes(3);
    private static MwProcess sim;
    private static int simPort;

    @BeforeAll
    static void start() throws Exception {
        PythonClient.python();
        simPort = Ports.free();
        sim = MwProcess.start("rosbridge-it-sim", "sim", MwProcess.CHECKOUT.resolve("examples/worlds/arena.yaml").toString(), "--rosbridge",
                String.valueOf(simPort));
        String line = sim.await("rosbridge at ", WITHIN);
        assertTrue(line.contains("ws://127.0.0.1:" + simPort + "/") && line.contains("/nxt") && line.contains("/ft"), line);
    }

    @AfterAll
    static void stop() throws InterruptedException {
        if (sim != null) {
            sim.close();
        }
    }

    @Test
    void roslibpyOverTwistedDrivesASimulatedRobot() throws Exception {
        PythonClient.Run r = PythonClient.run("roslibpy_client.py", Map.of("ROSLIBPY_TRANSPORT", "twisted"), SCRIPT, String.valueOf(simPort), "nxt",
                "/nxt/range/sonar");
        assertEquals(0, r.exit(), "roslibpy (twisted) against mw sim --rosbridge:\n" + r.output() + "\n(RoboMW's log: target/it-logs/rosbridge-it-sim.log)");
        assertTrue(r.output().contains("[twisted] PASS"), r.output());
    }

    @Test
    void roslibpyOverAsyncioDrivesAnotherSimulatedRobot() throws Exception {
        PythonClient.Run r = PythonClient.run("roslibpy_client.py", Map.of("ROSLIBPY_TRANSPORT", "asyncio"), SCRIPT, String.valueOf(simPort), "ft",
                "/ft/range/range");
        assertEquals(0, r.exit(), "roslibpy (asyncio) against mw sim --rosbridge:\n" + r.output() + "\n(RoboMW's log: target/it-logs/rosbridge-it-sim.log)");
        assertTrue(r.output().contains("[asyncio] PASS"), r.output());
    }

    @Test
    void roslibpyDrivesARobotServedByAnotherProcessThroughMwRosbridge() throws Exception {
        int robotPort = Ports.free();
        int bridgePort = Ports.free();
        java.nio.file.Path password = servePassword();
        try (MwProcess host = MwProcess.start("rosbridge-it-host", "host", "--name", "served", "--port", String.valueOf(Ports.free()), "--world",
                MwProcess.CHECKOUT.resolve("examples/worlds/arena.yaml").toString(), "--world-robot", "nxt", "--serve", "tcp://127.0.0.1:" + robotPort,
                "--no-wire", "--key-file", keyFile().toString(), "--serve-password-file", password.toString())) {
            host.await("robot nxt served at", WITHIN);
            // a served robot needs its password (issue 37): the caller's address names the file it is in
            try (MwProcess bridge = MwProcess.start("rosbridge-it-bridge", "rosbridge", "tcp://127.0.0.1:" + robotPort + "/nxt?password-file=" + password, "--port",
                    String.valueOf(bridgePort))) {
                bridge.await("rosbridge at ", WITHIN);
                PythonClient.Run r = PythonClient.run("roslibpy_client.py", Map.of("ROSLIBPY_TRANSPORT", "twisted"), SCRIPT, String.valueOf(bridgePort),
                        "nxt", "/nxt/range/sonar");
                assertEquals(0, r.exit(), "roslibpy against mw rosbridge over a served robot:\n" + r.output()
                        + "\n(logs: target/it-logs/rosbridge-it-host.log, rosbridge-it-bridge.log)");
            }
        }
    }

    private static java.nio.file.Path keyFile() throws IOException {
        java.nio.file.Path f = java.nio.file.Files.createTempFile("rosbridge-it", ".key");
        java.nio.file.Files.writeString(f, "rosbridge it cluster passphrase\n");
        f.toFile().deleteOnExit();
        return f;
    }

    /** The served robot's password, in a file only this user reads (as docs/security.md asks). */
    private static java.nio.file.Path servePassword() throws IOException {
        java.nio.file.Path f = java.nio.file.Files.createTempFile("rosbridge-it", ".password",
                java.nio.file.attribute.PosixFilePermissions.asFileAttribute(java.nio.file.attribute.PosixFilePermissions.fromString("rw-------")));
        java.nio.file.Files.writeString(f, "rosbridge it robot password\n");
        f.toFile().deleteOnExit();
        return f;
    }
}
