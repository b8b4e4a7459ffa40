package io.robomw.it.agents;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.mqtt.BrokerDirectory;
import io.robomw.it.messaging.PeerProcess;
import io.robomw.it.mqtt.Broker;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An agent's home events through a broker: a dispatcher (its own JVM, its node at the broker with
 * a persistent session) sends an agent to a host that is only at the broker; its reports come home
 * through the broker; the dispatcher is frozen (SIGSTOP) until the broker takes it as gone, the
 * agent ends meanwhile, and when the dispatcher is back (SIGCONT) the broker hands it the result it
 * kept for it.
 */
class BrokerEventsIT {

    private static final Duration WAIT = Duration.ofSeconds(60);

    @TempDir
    Path dir;

    @Test
    void aDispatcherAwayGetsItsAgentsResultThroughTheBrokerWhenItIsBack() throws Exception {
        try (Broker broker = Broker.start(Broker.Kind.EMBEDDED, "events-broker");
             HostProcess host = HostProcess.start("be-b", "--key-file", AgentTripIT.keyFile(dir).toString(), "--messaging", broker.address());
             PeerProcess home = PeerProcess.start("be-home", HomeProgram.class.getName(), List.of("-XX:+UseSerialGC"),
                     List.of(broker.address() + "?session-expiry=600&keep-alive=2", host.address()));
             MessagingNode poker = MessagingNode.builder("be-poker").bind(broker.address()).build()) {
            home.expect("READY", WAIT);
            home.expect("SENT", WAIT);
            home.expect("REPORT listening", WAIT);
            awaitLog(host, "REPORT of agent \\S+ delivered to its home \\S+ through broker"); // the home is announced there
            signal("STOP", home.process());
            try {
                awaitPresence(broker, "be-home", false);
                poker.publishMessage("poke", "wake up", "poke", null);
                // Tried while the home is away: a host says so once per home (and then once per log interval), not at every retry.
                awaitLog(host, "home \\S+ does not take deliveries");
            } finally {
                signal("CONT", home.process());
            }
            assertEquals("RESULT heard wake up from be-poker", home.expect("RESULT", WAIT));
            awaitLog(host, "RESULT of agent \\S+ delivered to its home \\S+ through broker");
        }
    }

    /** Waits until the host logged a line about the event (a retry while the home is away, or its delivery). */
    private static void awaitLog(HostProcess host, String regex) throws Exception {
        java.util.regex.Pattern p = java.util.regex.Pattern.compile(regex);
        Await.until("a line of the host's log matches '" + regex + "'", WAIT, () -> {
            try {
                return p.matcher(host.log()).find();
            } catch (java.io.IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
        });
    }

    private static void awaitPresence(Broker broker, String node, boolean online) throws Exception {
        try (BrokerDirectory d = BrokerDirectory.open(broker.address(), Duration.ofSeconds(10))) {
            Await.until((online ? "an online" : "an offline") + " presence of " + node, WAIT,
                    () -> d.records().stream().anyMatch(p -> p.node().equals(node) && p.online() == online), () -> String.valueOf(d.records()));
        }
    }

    private static void signal(String signal, Process p) throws Exception {
        Process kill = new ProcessBuilder("kill", "-" + signal, Long.toString(p.pid())).inheritIO().start();
        assertTrue(kill.waitFor(10, TimeUnit.SECONDS) && kill.exitValue() == 0, "kill -" + signal + " " + p.pid());
    }
}
