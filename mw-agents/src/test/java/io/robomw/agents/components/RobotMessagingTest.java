package io.robomw.agents.components;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import io.robomw.api.spi.MessagingConfig;
import io.robomw.api.spi.SecretRef;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A robot's communication component: when it starts, where it listens, and topic passwords from its robot file. */
class RobotMessagingTest {

    private static final Map<String, String> ENV = Map.of("ALERTS_PASSWORD", "s3cret");
    private final List<AutoCloseable> open = new ArrayList<>();

    @AfterEach
    void closeAll() throws Exception {
        for (AutoCloseable c : open) {
            c.close();
        }
    }

    private <T extends AutoCloseable> T opened(T c) {
        open.add(0, c);
        return c;
    }

    private RobotMessaging messaging(MessagingConfig config) {
        return opened(new RobotMessaging(config, MessagingSettings.defaults(), ENV::get));
    }

    @Test
    void withoutListenAddressesItStartsOnFirstUseOnLoopback() {
        RobotMessaging m = messaging(MessagingConfig.defaults("nxt-1", "nxt.yaml"));
        assertEquals(List.of(), m.addresses(), "nothing is bound before the first use");
        m.subscribeMessage("news", null);
        assertEquals(1, m.addresses().size());
        assertTrue(m.addresses().get(0).startsWith("tcp://127.0.0.1:"), m.addresses().toString());
        assertEquals("nxt-1", m.node().name());
    }

    @Test
    void withListenAddressesItStartsWhenTheRobotOpensAndConnectsToItsPeers() {
        MessagingNode peer = opened(MessagingNode.builder("peer").bind("tcp://127.0.0.1:0").build());
        List<Message> received = new CopyOnWriteArrayList<>();
        peer.addMessageListener("news", null, received::add);
        peer.subscribeMessage("news", null);
        RobotMessaging m = messaging(new MessagingConfig("nxt-1", List.of("tcp://127.0.0.1:0"), List.of(peer.address("tcp")), Map.of(), "nxt.yaml"));
        assertEquals(1, m.addresses().size(), "bound at open");
        Await.until("the peer's subscription reaches the robot's node", Duration.ofSeconds(10), () -> m.node().subscriberCount("news") == 1);
        m.publishMessage("news", "hello", "read", null);
        Await.until("the publication reaches the peer", Duration.ofSeconds(10), () -> received.size() == 1);
        assertEquals("nxt-1", received.get(0).sender());
    }

    @Test
    void anAddressInUseFailsTheOpenNamingIt() throws IOException {
        try (ServerSocket taken = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            String address = "tcp://127.0.0.1:" + taken.getLocalPort();
            MessagingException e = assertThrows(MessagingException.class,
                    () -> messaging(new MessagingConfig("nxt-1", List.of(address), List.of(), Map.of(), "nxt.yaml")));
            assertTrue(e.getMessage().contains(address), e.getMessage());
        }
    }

    @Test
    void aTopicWhosePasswordTheRobotFileNamesUsesItWhenTheCallerPassesNone() {
        MessagingNode peer = opened(MessagingNode.builder("peer").bind("tcp://127.0.0.1:0").build());
        List<Message> received = new CopyOnWriteArrayList<>();
        peer.addMessageListener("alerts", "s3cret", received::add);
        RobotMessaging m = messaging(new MessagingConfig("nxt-1", List.of(), List.of(),
                Map.of("alerts", new SecretRef(SecretRef.Kind.ENVIRONMENT, "ALERTS_PASSWORD", "nxt.yaml")), "nxt.yaml"));
        m.sendMessage("peer", peer.address("tcp"), null, "alerts", "fire", "alarm");
        Await.until("the protected message reaches the listener", Duration.ofSeconds(10), () -> received.size() == 1);
        assertEquals("fire", received.get(0).payload());
        assertEquals("s3cret", m.password("alerts", null));
        assertEquals("given", m.password("alerts", "given"), "a password passed explicitly wins");
        assertEquals(null, m.password("open-topic", null));
    }

    @Test
    void aPasswordThatCannotBeReadIsAClearErrorNamingTheRobotFile() {
        RobotMessaging m = messaging(new MessagingConfig("nxt-1", List.of(), List.of(),
                Map.of("alerts", new SecretRef(SecretRef.Kind.ENVIRONMENT, "UNSET_VARIABLE", "nxt.yaml")), "nxt.yaml"));
        MessagingException e = assertThrows(MessagingException.class, () -> m.publishMessage("alerts", "x", "f", null));
        assertTrue(e.getMessage().contains("nxt.yaml") && e.getMessage().contains("UNSET_VARIABLE"), e.getMessage());
    }

    @Test
    void aClosedComponentRefusesCalls() {
        RobotMessaging m = messaging(MessagingConfig.defaults("nxt-1", "nxt.yaml"));
        m.close();
        assertThrows(MessagingException.class, () -> m.publishMessage("news", "x", "f", null));
    }
}
