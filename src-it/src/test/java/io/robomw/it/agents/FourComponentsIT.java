package io.robomw.it.agents;

import io.robomw.testkit.Await;
import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.trip.ChatCaller;
import io.robomw.agents.host.trip.ChatResponder;
import io.robomw.api.AgentRef;
import io.robomw.it.demo.MwProcess;
import io.robomw.it.messaging.PeerProcess;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.Serializable;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * The paper's Instruction Layer linked across processes: agents on two {@code mw host} JVMs talk
 * to each other by host name through their hosts' messaging nodes; a plain program's robot (its
 * own JVM, {@code Robots.open} on an emulated NXT, or {@code Robots.remote} on a served robot)
 * publishes to an agent's listener on a host and sends an agent whose code only the program has.
 */
class FourComponentsIT {

    private static final String ALERTS_PASSWORD = "alerts-password";
    private static final Duration WAIT = Duration.ofSeconds(60);

    @TempDir
    static Path dir;
    static Path keyFile;
    static Path robotPassword;
    static HostProcess a;
    static HostProcess b;
    static AgentHost home;

    @BeforeAll
    static void startHosts() throws Exception {
        assertFalse(HostProcess.middlewareOnlyClassPath().contains("test-classes"), "the hosts must not have the test agents");
        keyFile = AgentTripIT.keyFile(dir);
        robotPassword = Files.writeString(dir.resolve("robot.password"), "four components\n");
        String world = AgentTripIT.world().toString();
        a = HostProcess.start("fc-a", "--world", world, "--world-robot", "sim-1", "--speed", "4", "--key-file", keyFile.toString());
        b = HostProcess.start("fc-b", "--world", world, "--world-robot", "sim-1", "--speed", "4", "--key-file", keyFile.toString(),
                "--serve", "tcp://127.0.0.1:0", "--serve-password-file", robotPassword.toString());
        home = AgentHost.builder("fc-home").clusterKey(AgentTripIT.KEY).start();
    }

    @AfterAll
    static void stopHosts() {
        if (home != null) {
            home.close();
        }
        for (HostProcess h : new HostProcess[] {a, b}) {
            if (h != null) {
                h.close();
            }
        }
    }

    /** Sends an agent from the test's home and waits for a report it gives when ready. */
    private static AgentRef sendAndAwaitReport(String host, io.robomw.api.Agent agent, String report) throws Exception {
        AgentRef ref = home.agency().sendAgent(host, agent);
        List<Serializable> reports = new CopyOnWriteArrayList<>();
        CompletableFuture<Void> ready = new CompletableFuture<>();
        ref.addReportListener(r -> {
            reports.add(r);
            if (report.equals(r)) {
                ready.complete(null);
            }
        });
        try {
            ready.get(WAIT.toSeconds(), TimeUnit.SECONDS);
        } catch (TimeoutException e) {
            fail("agent at " + host + " did not report '" + report + "' within " + WAIT + "; it reported " + reports + ", status " + ref.status());
        }
        return ref;
    }

    /** Publishes through the program every 200 ms until the listener has heard (pub/sub is fire and forget). */
    private static String publishUntilHeard(PeerProcess program, String command, AgentRef listener) throws Exception {
        Await.until("the listener hears a publication", WAIT, () -> {
            try {
                program.ask(command, "PUBLISHED");
                return listener.result().get(200, TimeUnit.MILLISECONDS) != null;
            } catch (TimeoutException notYet) {
                return false; // not heard yet: publish again
            } catch (Exception e) {
                throw new AssertionError(e);
            }
        });
        return (String) listener.result().get(WAIT.toMillis(), TimeUnit.MILLISECONDS);
    }

    @Test
    void twoAgentsOnTwoHostsExchangeARequestReplyAndAPublicationOnAProtectedTopicByHostName() throws Exception {
        AgentRef responder = sendAndAwaitReport(b.address(), new ChatResponder(), "ready");
        AgentRef caller = home.agency().sendAgent(a.address(), new ChatCaller("fc-b"));
        assertEquals("pong from fc-b", caller.result().get(WAIT.toSeconds(), TimeUnit.SECONDS));
        assertEquals("heard news from fc-a", responder.result().get(WAIT.toSeconds(), TimeUnit.SECONDS));
    }

    @Test
    void aPlainProgramsRobotPublishesToAnAgentsListenerAndSendsAnAgentFromAJarTheHostLacks() throws Exception {
        List<AutoCloseable> running = new ArrayList<>();
        try {
            MwProcess brick = MwProcess.start("fc-emulate-nxt", "emulate", "nxt", "--world", "examples/worlds/arena.yaml", "--robot", "nxt");
            running.add(brick);
            String device = brick.await("/dev/", WAIT).strip();
            Files.writeString(dir.resolve("alerts.key"), ALERTS_PASSWORD + "\n");
            String robot = Files.readString(MwProcess.CHECKOUT.resolve("examples/robots/nxt-two-wheeled.yaml"))
                    .replace("/dev/rfcomm0", device) + """
                    messaging:
                      connect: %s
                      topics:
                        alerts: { password_file: alerts.key }
                    agency:
                      key_file: %s
                    """.formatted(a.messaging(), keyFile);
            Path robotFile = Files.writeString(dir.resolve("nxt-program.yaml"), robot);
            AgentRef listener = sendAndAwaitReport(a.address(), new ListenerAgent("alerts", ALERTS_PASSWORD), "listening");
            PeerProcess program = PeerProcess.start("fc-program-open", RobotProgram.class.getName(), List.of("-XX:+UseSerialGC"),
                    List.of("open", robotFile.toString()));
            running.add(0, program);
            program.expect("READY nxt-1", WAIT);
            program.ask("move 0.1", "MOVED", WAIT);
            assertEquals("heard moved from nxt-1", publishUntilHeard(program, "publish alerts - moved", listener));
            String result = program.ask("send-agent " + b.address(), "RESULT", Duration.ofMinutes(2));
            assertTrue(result.matches(".*distanceDriven=0\\.8000.*"), result);
        } finally {
            for (AutoCloseable c : running) {
                c.close();
            }
        }
    }

    @Test
    void theSameThroughRobotsRemote() throws Exception {
        Path userHome = Files.createDirectories(dir.resolve("remote-user"));
        Files.createDirectories(userHome.resolve(".robomw"));
        Files.copy(keyFile, userHome.resolve(".robomw/cluster.key"));
        AgentRef listener = sendAndAwaitReport(b.address(), new ListenerAgent("alerts", ALERTS_PASSWORD), "listening");
        try (PeerProcess program = PeerProcess.start("fc-program-remote", RobotProgram.class.getName(),
                List.of("-XX:+UseSerialGC", "-Duser.home=" + userHome), List.of("remote", b.served() + "?password-file=" + robotPassword))) {
            program.expect("READY sim-1", WAIT);
            program.ask("move 0.1", "MOVED", WAIT);
            String heard = publishUntilHeard(program, "publish alerts " + ALERTS_PASSWORD + " moved-remotely", listener);
            assertTrue(heard.startsWith("heard moved-remotely from remote-sim-1"), heard);
            String result = program.ask("send-agent " + a.address(), "RESULT", Duration.ofMinutes(2));
            assertTrue(result.matches(".*distanceDriven=0\\.8000.*"), result);
        }
    }
}
