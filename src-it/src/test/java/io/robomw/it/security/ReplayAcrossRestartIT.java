package io.robomw.it.security;

import io.robomw.testkit.Ports;
import io.robomw.it.agents.HostProcess;
import io.robomw.it.demo.MwProcess;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.Socket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.HexFormat;
import java.util.Properties;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 3: replay protection did not survive a restart. A captured signed
 * {@code mw msg send} replayed to a restarted receiver was delivered again (and answered with a
 * signed echo); a sniffed signed robot {@code Move} re-published on the broker after the host
 * restarted moved the robot. Now a receiver keeps its replay window on disk, and refuses both.
 * Presences too: a signed presence captured at a broker and published again there (retained, so
 * every later reader gets it) is not believed by a reader that took a newer one, even after that
 * reader restarted.
 */
class ReplayAcrossRestartIT {

    /** The topic of the sniffer's own message that ends its capture (no node reads it). */
    private static final String END_OF_CAPTURE = "robomw/msg/replay-it-sniffer/end-of-capture";

    @TempDir
    Path dir;

    private static String log(String name) {
        try {
            Path f = Path.of("target", "it-logs", name + ".log");
            return Files.exists(f) ? Files.readString(f) : "";
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    @Test
    void aCapturedSignedMessageReplayedToARestartedReceiverIsRefused() throws Exception {
        Path password = Files.writeString(dir.resolve("topic.password"), "s3cret\n");
        String name = "replay-echoer-" + Long.toHexString(new SecureRandom().nextLong());
        int port = Ports.free();
        String[] receiver = {"msg", "sub", "tcp://127.0.0.1:" + port, "cmd", "--bind", "--echo", "--password-file", password.toString(), "--name", name};
        byte[] captured;
        try (MwProcess first = MwProcess.start("replay-receiver", receiver)) {
            first.await("listening to topic", Duration.ofSeconds(60));
            try (TcpTap tap = new TcpTap(port);
                 MwProcess send = MwProcess.start("replay-send", "msg", "send", "tcp://127.0.0.1:" + tap.port(), name, "cmd", "open the door",
                         "--password-file", password.toString())) {
                assertEquals(0, send.waitFor(Duration.ofSeconds(60)), send.output());
                captured = tap.sentToServer();
            }
            first.await("open the door", Duration.ofSeconds(30));
        }
        try (MwProcess restarted = MwProcess.start("replay-receiver-restarted", receiver)) {
            restarted.await("listening to topic", Duration.ofSeconds(60));
            try (Socket attacker = new Socket("127.0.0.1", port)) {
                attacker.getOutputStream().write(captured);
                attacker.getOutputStream().flush();
                Await.until("the restarted receiver refuses the replayed message, or takes it", Duration.ofSeconds(60),
                        () -> log("replay-receiver-restarted").contains("before this node restarted") || restarted.output().contains("open the door"),
                        () -> log("replay-receiver-restarted"));
            }
            assertFalse(restarted.output().contains("open the door"), "the replay was delivered again: " + restarted.output());
            assertTrue(log("replay-receiver-restarted").contains("before this node restarted"));
        }
    }

    @Test
    void aSniffedRobotMoveRepublishedAtTheBrokerAfterTheHostRestartedIsRefused() throws Exception {
        MqttClients.assumeInstalled();
        Path credentials = dir.resolve("broker.credentials");
        Path password = Files.writeString(dir.resolve("robot.password"), "robot s3cret\n");
        Path key = Attacker.keyFile(dir);
        int port = Ports.free();
        String world = Path.of(ReplayAcrossRestartIT.class.getResource("/robots/sim-world.yaml").toURI()).toString();
        try (MwProcess broker = MwProcess.start("replay-broker", "broker", "--port", String.valueOf(port), "--credentials", credentials.toString(),
                "--data", dir.resolve("broker").toString())) {
            broker.await("mqtt broker ready", Duration.ofSeconds(60));
            Properties c = new Properties();
            try (var r = Files.newBufferedReader(credentials)) {
                c.load(r);
            }
            String user = c.getProperty("username");
            String pass = c.getProperty("password");
            String at = "mqtt://127.0.0.1:" + port;
            // A name of its own, as the tests above: a node's replay window is a file per node name in the user's home, which
            // one process at a time holds; a host of the same name elsewhere (another build's run of this test) would leave
            // this one's window in memory only, and the replay after the restart would be taken.
            String hostName = "replay-robot-host-" + Long.toHexString(new SecureRandom().nextLong());
            try (HostProcess host = HostProcess.start(hostName, "--world", world, "--world-robot", "sim-1", "--key-file", key.toString(),
                    "--serve", at + "?credentials=" + credentials, "--serve-password-file", password.toString())) {
                // someone who can read the broker's traffic records the robot's commands (90 s at most), until the end of the
                // capture: a message of its own on the same topics, published once the move is over
                Process sniffer = new ProcessBuilder("/usr/bin/mosquitto_sub", "-h", "127.0.0.1", "-p", String.valueOf(port), "-u", user, "-P", pass,
                        "-t", "robomw/msg/#", "-q", "1", "-W", "90", "-F", "%t %x").redirectErrorStream(true).start();
                Await.until("the sniffer subscribed", Duration.ofSeconds(30), () -> {
                    try {
                        return MqttClients.sub(port, user, pass, "-t", "robomw/presence/+", "-C", "1", "-W", "10").status() == 0;
                    } catch (IOException | InterruptedException e) {
                        return false;
                    }
                });
                String robot = at + "/sim-1?credentials=" + credentials + "&password-file=" + password;
                try (MwProcess move = MwProcess.start("replay-robot-move", "robot", robot, "move", "0.3", "0.2")) {
                    assertEquals(0, move.waitFor(Duration.ofSeconds(60)), move.output());
                }
                MqttClients.Run end = MqttClients.pub(port, user, pass, "-q", "1", "-t", END_OF_CAPTURE, "-m", "end");
                assertEquals(0, end.status(), end.output());
                java.util.List<String[]> sniffed = new java.util.ArrayList<>();
                boolean ended = false;
                // mosquitto_sub writes each message as it comes; it ends by itself after 90 s at most (-W)
                try (var lines = new java.io.BufferedReader(new java.io.InputStreamReader(sniffer.getInputStream(), java.nio.charset.StandardCharsets.UTF_8))) {
                    for (String line; !ended && (line = lines.readLine()) != null; ) {
                        ended = line.startsWith(END_OF_CAPTURE + " ");
                        if (!ended && line.startsWith("robomw/msg/")) {
                            sniffed.add(line.strip().split(" ", 2));
                        }
                    }
                } finally {
                    sniffer.destroy();
                }
                assertTrue(sniffer.waitFor(30, TimeUnit.SECONDS), "the sniffer ended");
                assertTrue(ended, "the sniffer saw the end of the capture: " + sniffed.size() + " messages before it");
                assertTrue(sniffed.size() >= 1, "the sniffer saw the robot's commands");

                host.kill();
                host.restart();
                String before = pose(robot);
                int i = 0;
                for (String[] s : sniffed) {
                    Path frame = Files.write(dir.resolve("command-" + i++ + ".frame"), HexFormat.of().parseHex(s[1]));
                    MqttClients.Run replayed = MqttClients.pub(port, user, pass, "-q", "1", "-t", s[0], "-f", frame.toString());
                    assertEquals(0, replayed.status(), replayed.output());
                }
                try {
                    Await.until("the restarted host refuses the replayed command", Duration.ofSeconds(60),
                            () -> {
                                try {
                                    return host.log().contains("before this node restarted");
                                } catch (IOException e) {
                                    return false;
                                }
                            }, () -> "");
                } catch (AssertionError notRefused) {
                    throw new AssertionError("the replayed command was not refused; the robot was at " + before + ", now " + pose(robot), notRefused);
                }
                assertEquals(before, pose(robot), "the robot did not move again");
            }
        }
    }

    @Test
    void aCapturedSignedPresenceRepublishedAtTheBrokerIsIgnoredByAReaderThatTookANewerOne() throws Exception {
        MqttClients.assumeInstalled();
        Path key = Attacker.keyFile(dir);
        int port = Ports.free();
        String name = "replay-presence-" + Long.toHexString(new SecureRandom().nextLong());
        String at = "mqtt://127.0.0.1:" + port;
        // a lab's shared broker, whose members may all publish presences (no access rules)
        try (MwProcess broker = MwProcess.start("replay-presence-broker", "broker", "--port", String.valueOf(port), "--anonymous",
                "--data", dir.resolve("broker").toString())) {
            broker.await("mqtt broker ready", Duration.ofSeconds(60));
            String[] captured;
            String address;
            try (HostProcess host = HostProcess.start(name, "--key-file", key.toString(), "--messaging", at)) {
                address = host.address();
                // a member of the lab records the host's signed presence
                String[] seen = {""};
                Await.until("the host's presence is at the broker", Duration.ofSeconds(60), () -> {
                    try {
                        MqttClients.Run r = MqttClients.sub(port, null, null, "-t", "robomw/presence/+", "-F", "%t %x", "-C", "1", "-W", "10");
                        seen[0] = r.output();
                        return r.status() == 0 && seen[0].startsWith("robomw/presence/");
                    } catch (IOException | InterruptedException e) {
                        throw new IllegalStateException(e);
                    }
                }, () -> seen[0]);
                captured = seen[0].lines().filter(l -> l.startsWith("robomw/presence/")).findFirst().orElseThrow().strip().split(" ", 2);
                assertTrue(new String(HexFormat.of().parseHex(captured[1])).contains("status online"), seen[0]);
                assertTrue(agents(at, key, dir.resolve("home"), out -> out.contains(address) && !out.contains("offline since")).contains(name + "  online"));
            }
            // the host is gone: this user's mw agents sees it offline (and keeps the newest presence it took, across its runs)
            agents(at, key, dir.resolve("home"), out -> out.contains("offline since"));
            Path frame = Files.write(dir.resolve("presence.frame"), HexFormat.of().parseHex(captured[1]));
            MqttClients.Run replayed = MqttClients.pub(port, null, null, "-r", "-q", "1", "-t", captured[0], "-f", frame.toString());
            assertEquals(0, replayed.status(), replayed.output());
            String listed = agents(at, key, dir.resolve("home"), out -> out.contains("presence record ignored") || out.contains(name + "  online"));
            assertFalse(listed.contains(name + "  online"), "the replayed presence lists the host online again, at an address nobody serves: " + listed);
            assertTrue(listed.contains("1 signed presence record ignored: older than one taken before"), listed);
        }
    }

    /** Runs mw agents --cluster (a new process each time) until its output passes, and returns that output. */
    private static String agents(String at, Path key, Path home, java.util.function.Predicate<String> done) {
        String[] listed = {""};
        // a reader takes what the broker sends within a moment of quiet: on a loaded machine it may ask again
        Await.until("mw agents --cluster", Duration.ofSeconds(120), () -> {
            // a home of its own: another test's mw agents running at the same time would hold ~/.robomw/replay's presence
            // window (one process at a time), and this one's would then not outlive its run
            try (MwProcess agents = MwProcess.startWithHome("replay-presence-agents", home, "agents", "--cluster", at, "--key-file", key.toString())) {
                agents.waitFor(Duration.ofSeconds(60));
                listed[0] = agents.output();
                return done.test(listed[0]);
            } catch (Exception e) {
                throw new IllegalStateException(e);
            }
        }, () -> listed[0]);
        return listed[0];
    }

    private static String pose(String robot) throws Exception {
        try (MwProcess pose = MwProcess.start("replay-robot-pose", "robot", robot, "pose")) {
            assertEquals(0, pose.waitFor(Duration.ofSeconds(60)), pose.output());
            return pose.output().strip();
        }
    }
}
