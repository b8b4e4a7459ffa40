package io.robomw.it.agents;

import io.robomw.it.demo.MwProcess;
import io.robomw.it.mqtt.Broker;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.atomic.AtomicReference;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw agents --cluster}: a host that drives a robot is listed with it, and a host killed
 * with -9 is listed offline since a time (its will, left at the broker when it joined, names it).
 */
class ClusterListIT {

    private static final Duration WAIT = Duration.ofSeconds(90);

    @TempDir
    Path dir;

    @Test
    void aHostThatDrivesARobotIsListedWithItAndAKilledHostOfflineSinceATime() throws Exception {
        try (Broker broker = Broker.start(Broker.Kind.EMBEDDED, "list-broker");
             HostProcess host = HostProcess.start("cl-a", "--world", AgentTripIT.world().toString(), "--world-robot", "sim-1", "--key-file",
                     AgentTripIT.keyFile(dir).toString(), "--messaging", broker.address() + "?keep-alive=2")) {
            String key = dir.resolve("cluster.key").toString();
            String online = list(broker, key, "cl-a  online  " + host.address());
            assertTrue(online.contains("cl-a  online  " + host.address() + "  robot sim-1"), "the robot it drives, asked of the host: " + online);
            host.kill();
            String offline = list(broker, key, "cl-a  offline since ");
            assertTrue(Pattern.compile("cl-a  offline since \\d{4}-\\d\\d-\\d\\dT[0-9:]+Z  " + Pattern.quote(host.address())).matcher(offline).find(),
                    "the killed host is listed offline since a time: " + offline);
        }
    }

    private static String list(Broker broker, String key, String expected) {
        AtomicReference<String> listed = new AtomicReference<>("");
        Await.until("mw agents --cluster lists '" + expected + "'", WAIT, () -> {
            try (MwProcess list = MwProcess.start("cl-agents", "agents", "--cluster", broker.address(), "--key-file", key)) {
                list.waitFor(WAIT);
                listed.set(list.output());
            } catch (Exception e) {
                throw new AssertionError(e);
            }
            return listed.get().contains(expected);
        }, listed::get);
        return listed.get();
    }
}
