package io.robomw.cli.broker;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The embedded broker against RoboMW nodes on loopback. */
class EmbeddedBrokerTest {

    private static final int BURST = 3_000;

    /**
     * A subscriber that cannot take anything for a while (its listener blocked, as on a loaded machine) gets
     * every message of a burst larger than HiveMQ's default queue of 1000 a client, in order, once it can.
     */
    @Test
    void aSlowSubscriberGetsEveryMessageOfABurstInOrder() throws Exception {
        CountDownLatch release = new CountDownLatch(1);
        List<Object> got = new ArrayList<>();
        try (EmbeddedBroker broker = EmbeddedBroker.start("127.0.0.1", 0, null);
             MessagingNode subscriber = MessagingNode.builder("slow").bind(broker.address()).build();
             MessagingNode observer = MessagingNode.builder("fast").bind(broker.address()).build();
             MessagingNode publisher = MessagingNode.builder("burst").bind(broker.address()).build()) {
            AtomicInteger seen = new java.util.concurrent.atomic.AtomicInteger();
            observer.addMessageListener("numbers", null, m -> seen.incrementAndGet());
            observer.subscribeMessage("numbers", null);
            subscriber.addMessageListener("numbers", null, m -> {
                try {
                    assertTrue(release.await(60, TimeUnit.SECONDS), "the test released the listener");
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
                synchronized (got) {
                    got.add(m.payload());
                }
            });
            subscriber.subscribeMessage("numbers", null);
            for (int i = 0; i < BURST; i++) {
                publisher.publishMessage("numbers", i, "count", null);
            }
            // The whole burst has passed the broker (a subscriber that keeps up has it) before the slow one takes any.
            Await.until("a subscriber that keeps up has the burst", Duration.ofSeconds(60), () -> seen.get() >= BURST,
                    () -> "; it has " + seen.get());
            release.countDown();
            Await.until("the subscriber has the burst", Duration.ofSeconds(60), () -> {
                synchronized (got) {
                    return got.size() >= BURST;
                }
            }, () -> "; got " + size(got));
            List<Object> expected = new ArrayList<>();
            for (int i = 0; i < BURST; i++) {
                expected.add(i);
            }
            synchronized (got) {
                assertEquals(expected, got);
            }
        }
    }

    private static int size(List<Object> got) {
        synchronized (got) {
            return got.size();
        }
    }
}
