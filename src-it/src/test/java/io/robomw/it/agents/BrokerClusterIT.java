package io.robomw.it.agents;

import io.robomw.testkit.Await;
import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.trip.ChatCaller;
import io.robomw.agents.host.trip.ChatResponder;
import io.robomw.api.AgentRef;
import io.robomw.it.demo.MwProcess;
import io.robomw.it.mqtt.Broker;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Two {@code mw host} JVMs whose messaging nodes are only at a broker ({@code --messaging mqtt://...}):
 * their agents talk to each other by host name through it, and {@code mw agents --cluster BROKER}
 * lists both hosts and their agents from what they announce there, and with the cluster key what
 * each owes homes (asked of the host). Agents still travel over RMI.
 */
class BrokerClusterIT {

    private static final Duration WAIT = Duration.ofSeconds(60);

    @TempDir
    static Path dir;
    static Broker broker;
    static HostProcess a;
    static HostProcess b;
    static AgentHost home;

    @BeforeAll
    static void start() throws Exception {
        broker = Broker.start(Broker.Kind.EMBEDDED, "cluster-broker");
        Path keyFile = AgentTripIT.keyFile(dir);
        String world = AgentTripIT.world().toString();
        a = HostProcess.start("bc-a", "--world", world, "--world-robot", "sim-1", "--speed", "4", "--key-file", keyFile.toString(),
                "--messaging", broker.address());
        b = HostProcess.start("bc-b", "--world", world, "--world-robot", "sim-1", "--speed", "4", "--key-file", keyFile.toString(),
                "--messaging", broker.address());
        home = AgentHost.builder("bc-home").clusterKey(AgentTripIT.KEY).start();
    }

    @AfterAll
    static void stop() {
        if (home != null) {
            home.close();
        }
        for (AutoCloseable c : new AutoCloseable[] {a, b, broker}) {
            if (c != null) {
                try {
                    c.close();
                } catch (Exception e) {
                    // closing anyway
                }
            }
        }
    }

    @Test
    void agentsOnTwoHostsTalkByHostNameThroughTheBrokerAndTheClusterIsListedFromItsPresence() throws Exception {
        assertTrue(a.messaging().startsWith("mqtt://"), a.messaging());
        AgentRef responder = home.agency().sendAgent(b.address(), new ChatResponder());
        CompletableFuture<Void> ready = new CompletableFuture<>();
        responder.addReportListener(r -> {
            if ("ready".equals(r)) {
                ready.complete(null);
            }
        });
        ready.get(WAIT.toSeconds(), TimeUnit.SECONDS);
        String expected = responder.id() + " " + ChatResponder.class.getName();
        java.util.concurrent.atomic.AtomicReference<String> listed = new java.util.concurrent.atomic.AtomicReference<>("");
        // a host announces its agents once a second: list again until the responder shows
        Await.until("mw agents lists the responder", WAIT, () -> {
            try (MwProcess list = MwProcess.start("bc-agents", "agents", "--cluster", broker.address())) {
                assertEquals(0, list.waitFor(WAIT));
                listed.set(list.output());
            } catch (Exception e) {
                throw new AssertionError(e);
            }
            return listed.get().contains(expected);
        }, listed::get);
        String out = listed.get();
        assertTrue(out.contains("2 agent hosts at " + broker.address()), out);
        assertTrue(out.contains("bc-a  online  " + a.address()) && out.contains("bc-b  online  " + b.address()), out);
        assertTrue(out.contains(expected), out);
        AgentRef caller = home.agency().sendAgent(a.address(), new ChatCaller("bc-b"));
        assertEquals("pong from bc-b", caller.result().get(WAIT.toSeconds(), TimeUnit.SECONDS));
        assertEquals("heard news from bc-a", responder.result().get(WAIT.toSeconds(), TimeUnit.SECONDS));

        // With the cluster key, every host online is asked what it owes homes, and --drop-owed drops it at each.
        String key = dir.resolve("cluster.key").toString();
        try (MwProcess owed = MwProcess.start("bc-owed", "agents", "--cluster", broker.address(), "--key-file", key)) {
            assertEquals(0, owed.waitFor(WAIT), owed.output());
            String text = owed.output();
            assertTrue(text.matches("(?s).*\\d+ deliver(y|ies) owed by " + Pattern.quote(a.address()) + ".*")
                    && text.matches("(?s).*\\d+ deliver(y|ies) owed by " + Pattern.quote(b.address()) + ".*"), text);
        }
        try (MwProcess drop = MwProcess.start("bc-drop", "agents", "--cluster", broker.address(), "--key-file", key, "--drop-owed", "all")) {
            assertEquals(0, drop.waitFor(WAIT), drop.output());
            assertTrue(drop.output().contains(a.address() + " dropped ") && drop.output().contains(b.address() + " dropped "), drop.output());
        }
    }
}
