package io.robomw.it.messaging;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInstance;

import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.NetworkInterface;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import java.util.UUID;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * One publisher (this JVM) and three subscriber JVMs in a multicast group, bound explicitly to
 * the loopback interface with TTL 0, so no datagram leaves the host.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
class MulticastMessagingIT {

    private static final Duration WAIT = Duration.ofSeconds(30);
    private final List<PeerProcess> subscribers = new ArrayList<>();
    private MessagingNode publisher;
    private String group;

    @BeforeAll
    void start() throws Exception {
        String loopback = NetworkInterface.getByInetAddress(InetAddress.getLoopbackAddress()).getName();
        int port;
        try (DatagramSocket s = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0))) {
            port = s.getLocalPort();
        }
        group = "multicast://239.255." + new Random().nextInt(255) + "." + (1 + new Random().nextInt(254)) + ":" + port
                + "?interface=" + loopback + "&ttl=0";
        for (int i = 1; i <= 3; i++) {
            PeerProcess p = PeerProcess.peer("mcast-" + i, List.of());
            subscribers.add(p);
            p.ask("bind " + group, "BOUND");
            p.ask("subscribe numbers -", "OK");
            p.ask("subscribe guarded right", "OK");
            p.ask("subscribe data -", "OK");
            p.ask("echo ask -", "OK");
        }
        publisher = MessagingNode.builder("mcast-publisher").bind(group).build();
    }

    @AfterAll
    void stop() {
        if (publisher != null) {
            publisher.close();
        }
        subscribers.forEach(PeerProcess::close);
    }

    @Test
    void threeSubscribersEachReceiveEveryPublication() {
        for (int from = 0; from < 1000; from += 100) {
            for (int i = from; i < from + 100; i++) {
                publisher.publishMessage("numbers", i, "count", null);
            }
            for (PeerProcess p : subscribers) {
                String count = p.ask("await numbers " + (from + 100) + " 20", "COUNT");
                assertEquals("COUNT numbers " + (from + 100) + " ordered=true", count);
            }
        }
        for (PeerProcess p : subscribers) {
            assertTrue(p.ask("stats", "STATS").contains(" lost=0 "));
        }
    }

    @Test
    void requestsToNamedMembersGetTheirOwnRepliesUnderConcurrency() throws Exception {
        ExecutorService pool = Executors.newFixedThreadPool(3);
        try {
            List<Future<?>> done = new ArrayList<>();
            for (int m = 1; m <= 3; m++) {
                String member = "mcast-" + m;
                done.add(pool.submit(() -> {
                    for (int i = 0; i < 50; i++) {
                        UUID id = publisher.sendMessage(member, group, null, "ask", member + "/" + i, "ask");
                        Message reply = publisher.waitForReply(id, WAIT);
                        assertEquals(member, reply.sender());
                        assertEquals(member + "/" + i, reply.payload());
                    }
                    return null;
                }));
            }
            for (Future<?> f : done) {
                f.get(WAIT.toSeconds(), TimeUnit.SECONDS);
            }
        } finally {
            pool.shutdownNow();
        }
    }

    @Test
    void publicationWithTheWrongPasswordIsRejectedByEveryMember() {
        publisher.publishMessage("guarded", 0, "go", "wrong");
        publisher.publishMessage("guarded", 0, "go", "right");
        for (PeerProcess p : subscribers) {
            assertEquals("COUNT guarded 1 ordered=true", p.ask("await guarded 1 20", "COUNT"));
            assertTrue(p.ask("stats", "STATS").contains(" BAD_MAC=1 "));
        }
    }

    @Test
    void payloadOfAClassNotOnTheAllowListIsRejectedByEveryMember() {
        publisher.publishMessage("data", new Secret("x"), "store", null);
        publisher.publishMessage("data", 0, "store", null);
        for (PeerProcess p : subscribers) {
            assertEquals("COUNT data 1 ordered=true", p.ask("await data 1 20", "COUNT"));
            assertTrue(p.ask("stats", "STATS").contains(" REJECTED_CLASS=1 "));
        }
    }
}
