package io.robomw.agents.messaging;

import io.robomw.testkit.Await;
import io.robomw.api.Message;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;

/** The same scenarios over every point-to-point transport, in this JVM on loopback. */
class EveryTransportTest {

    private static final Duration WAIT = Duration.ofSeconds(10);
    private final List<MessagingNode> nodes = new CopyOnWriteArrayList<>();

    @AfterEach
    void closeNodes() {
        nodes.forEach(MessagingNode::close);
    }

    private MessagingNode node(MessagingNode.Builder b) {
        MessagingNode n = b.build();
        nodes.add(n);
        return n;
    }

    private static String bindAddress(String scheme) {
        return scheme.equals("rmi") ? "rmi://127.0.0.1:0/server" : scheme + "://127.0.0.1:0";
    }

    /** TCP and RMI are reliable and ordered per connection or session (docs/messaging.md, "Addresses and transports"). */
    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void aReliableTransportDeliversEveryPublicationInOrder(String scheme) {
        MessagingNode pub = node(MessagingNode.builder("pub").bind(bindAddress(scheme)));
        MessagingNode sub = node(MessagingNode.builder("sub").connect(pub.address(scheme)));
        List<Object> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener("numbers", "pw", m -> got.add(m.payload()));
        sub.subscribeMessage("numbers", "pw");
        Await.until("publisher sees the subscriber", WAIT, () -> pub.subscriberCount("numbers") == 1);
        for (int i = 0; i < 200; i++) {
            pub.publishMessage("numbers", i, "count", "pw");
        }
        Await.until("200 publications arrive", WAIT, () -> got.size() == 200);
        List<Object> expected = new ArrayList<>();
        for (int i = 0; i < 200; i++) {
            expected.add(i);
        }
        assertEquals(expected, got);
    }

    /**
     * UDP promises neither delivery, nor order, nor uniqueness (docs/messaging.md, "What UDP and
     * multicast do not guarantee"): what it promises is that what arrives is what was published,
     * intact and authenticated. Publications go on until a hundred have arrived.
     */
    @org.junit.jupiter.api.Test
    void udpDeliversIntactWhatArrivesOfWhatThePublisherSends() {
        MessagingNode pub = node(MessagingNode.builder("pub").bind(bindAddress("udp")));
        MessagingNode sub = node(MessagingNode.builder("sub").connect(pub.address("udp")));
        List<Message> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener("numbers", "pw", got::add);
        sub.subscribeMessage("numbers", "pw");
        Await.until("publisher sees the subscriber", WAIT, () -> pub.subscriberCount("numbers") == 1);
        List<Integer> sent = new ArrayList<>();
        Await.until("a hundred publications arrive", WAIT, () -> {
            if (sent.size() < 100_000) {
                pub.publishMessage("numbers", sent.size(), "count", "pw");
                sent.add(sent.size());
            }
            return got.size() >= 100;
        }, () -> got.size() + " arrived of " + sent.size() + " sent");
        for (Message m : got) {
            assertEquals("pub", m.sender());
            assertEquals("numbers", m.topic());
            assertEquals("count", m.function());
            org.junit.jupiter.api.Assertions.assertTrue(m.payload() instanceof Integer i && i >= 0 && i < sent.size(),
                    "a publication that was sent: " + m.payload());
        }
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "udp", "rmi"})
    void concurrentRequestsEachGetTheirOwnReply(String scheme) throws Exception {
        MessagingNode server = node(MessagingNode.builder("server").bind(bindAddress(scheme)));
        server.addMessageListener("square", null, m -> server.replyMessage(m, (Integer) m.payload() * (Integer) m.payload(), "ok"));
        MessagingNode client = node(MessagingNode.builder("client"));
        String host = server.address(scheme);
        List<Thread> threads = new ArrayList<>();
        List<Throwable> failures = new CopyOnWriteArrayList<>();
        for (int t = 0; t < 4; t++) {
            int base = t * 1000;
            Thread thread = new Thread(() -> {
                try {
                    for (int i = base; i < base + 50; i++) {
                        UUID id = client.sendMessage("server", host, null, "square", i, "square");
                        Message reply = client.waitForReply(id, WAIT);
                        assertEquals(i * i, reply.payload());
                        assertEquals(id, reply.correlationId());
                    }
                } catch (Throwable e) {
                    failures.add(e);
                }
            });
            threads.add(thread);
            thread.start();
        }
        for (Thread t : threads) {
            t.join(WAIT.toMillis());
        }
        assertEquals(List.of(), failures);
    }

    @org.junit.jupiter.api.Test
    void frameLargerThanADatagramIsRefusedAndTheLinkStaysUsable() {
        MessagingNode server = node(MessagingNode.builder("server").bind("udp://127.0.0.1:0"));
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node(MessagingNode.builder("client"));
        String host = server.address("udp");
        io.robomw.api.MessagingException e = org.junit.jupiter.api.Assertions.assertThrows(io.robomw.api.MessagingException.class,
                () -> client.sendMessage("server", host, null, "echo", new byte[70_000], "big"));
        org.junit.jupiter.api.Assertions.assertTrue(e.getMessage().contains("one datagram"), e.getMessage());
        UUID id = client.sendMessage("server", host, null, "echo", "small", "ok");
        assertEquals("small", client.waitForReply(id, WAIT).payload());
    }

    @org.junit.jupiter.api.Test
    void everyMulticastMemberReceivesThePublications() {
        String group = "multicast://239.255.77." + (1 + new java.util.Random().nextInt(250)) + ":" + FreePorts.udp()
                + "?interface=" + FreePorts.loopbackInterface() + "&ttl=0";
        MessagingNode pub = node(MessagingNode.builder("pub").bind(group));
        List<List<Object>> got = new ArrayList<>();
        for (int s = 0; s < 2; s++) {
            MessagingNode sub = node(MessagingNode.builder("sub" + s).bind(group));
            List<Object> mine = new CopyOnWriteArrayList<>();
            got.add(mine);
            sub.addMessageListener("numbers", null, m -> mine.add(m.payload()));
            sub.subscribeMessage("numbers", null);
        }
        // Multicast promises no delivery (docs/messaging.md): publications go on until each member has a hundred.
        List<Integer> sent = new ArrayList<>();
        Await.until("each member receives a hundred publications", WAIT, () -> {
            if (sent.size() < 100_000) {
                pub.publishMessage("numbers", sent.size(), "count", null);
                sent.add(sent.size());
            }
            return got.stream().allMatch(mine -> mine.size() >= 100);
        }, () -> got.stream().map(List::size).toList() + " arrived of " + sent.size() + " sent");
        for (List<Object> mine : got) {
            org.junit.jupiter.api.Assertions.assertTrue(mine.stream().allMatch(p -> p instanceof Integer i && i >= 0 && i < sent.size()),
                    "only publications that were sent: " + mine);
        }
    }
}
