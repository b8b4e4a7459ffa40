package io.robomw.it.messaging;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInstance;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The scenarios every point-to-point transport must pass, between this JVM and a {@link Peer} in
 * another JVM on loopback: request/reply with correlation under concurrency, wrong password
 * rejected, non-allow-listed class rejected. Subclasses add the delivery test fit for their
 * transport.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
abstract class PointToPointIT {

    static final Duration WAIT = Duration.ofSeconds(30);

    PeerProcess peer;
    String peerAddress;
    MessagingNode local;

    /** @return where the peer binds, for example {@code tcp://127.0.0.1:0} */
    abstract String bindAddress();

    @BeforeAll
    void start() throws Exception {
        peer = PeerProcess.peer("peer-" + getClass().getSimpleName(), List.of());
        peerAddress = peer.ask("bind " + bindAddress(), "BOUND").substring("BOUND ".length());
        peer.ask("echo echo -", "OK");
        peer.ask("listen guarded right", "OK");
        peer.ask("listen data -", "OK");
        local = MessagingNode.builder("local-" + getClass().getSimpleName()).build();
    }

    @AfterAll
    void stop() {
        if (local != null) {
            local.close();
        }
        if (peer != null) {
            peer.close();
        }
    }

    @Test
    void concurrentRequestsEachGetTheirOwnReply() throws Exception {
        ExecutorService pool = Executors.newFixedThreadPool(8);
        try {
            List<Future<?>> done = new ArrayList<>();
            for (int t = 0; t < 8; t++) {
                int thread = t;
                done.add(pool.submit(() -> {
                    for (int i = 0; i < 100; i++) {
                        String payload = "t" + thread + "-" + i;
                        UUID id = local.sendMessage(peerName(), peerAddress, null, "echo", payload, "ask");
                        Message reply = local.waitForReply(id, WAIT);
                        assertEquals(payload, reply.payload());
                        assertEquals(id, reply.correlationId());
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
    void messageWithTheWrongPasswordIsRejected() {
        long before = dropped("BAD_MAC");
        local.sendMessage(peerName(), peerAddress, "wrong", "guarded", 0, "go");
        waitUntil(() -> dropped("BAD_MAC") == before + 1);
        assertTrue(peer.ask("count guarded", "COUNT").startsWith("COUNT guarded 0 "));
        local.sendMessage(peerName(), peerAddress, "right", "guarded", 0, "go");
        assertTrue(peer.ask("await guarded 1 20", "COUNT").startsWith("COUNT guarded 1 "));
    }

    @Test
    void payloadOfAClassNotOnTheAllowListIsRejected() {
        UUID id = local.sendMessage(peerName(), peerAddress, null, "data", new Secret("x"), "store");
        MessagingException e = assertThrows(MessagingException.class, () -> local.waitForReply(id, WAIT));
        assertTrue(e.getMessage().contains(Secret.class.getName()), e.getMessage());
        assertEquals(1, dropped("REJECTED_CLASS"));
        assertTrue(peer.ask("count data", "COUNT").startsWith("COUNT data 0 "));
    }

    String peerName() {
        return "peer-" + getClass().getSimpleName();
    }

    long dropped(String reason) {
        String stats = peer.ask("stats", "STATS");
        for (String part : stats.split(" ")) {
            if (part.startsWith(reason + "=")) {
                return Long.parseLong(part.substring(reason.length() + 1));
            }
        }
        throw new AssertionError("no " + reason + " in " + stats);
    }

    static void waitUntil(java.util.function.BooleanSupplier condition) {
        Await.until("the condition", WAIT, condition);
    }

    /** Subscribes this JVM to the peer's publications on {@code topic}. */
    List<Object> subscribeToPeer(String topic) {
        List<Object> got = new CopyOnWriteArrayList<>();
        local.connect(peerAddress);
        local.addMessageListener(topic, null, m -> got.add(m.payload()));
        local.subscribeMessage(topic, null);
        assertEquals("SUBS 1", peer.ask("waitsubs " + topic + " 1 20", "SUBS"));
        return got;
    }

    static void assertInOrder(List<Object> got, int n) {
        assertEquals(n, got.size());
        for (int i = 0; i < n; i++) {
            assertEquals(i, got.get(i), "message " + i);
        }
    }
}
