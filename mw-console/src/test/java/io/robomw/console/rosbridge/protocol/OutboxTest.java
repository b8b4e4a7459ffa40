package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.databind.node.JsonNodeFactory;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.graph.Publication;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** What waits for one client is bounded, however slow it is, and sending never recurses. */
class OutboxTest {

    private final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(r -> new Thread(r, "outbox-test-timer"));

    @AfterEach
    void stop() {
        timer.shutdownNow();
    }

    private static Publication message(int i, int chars) {
        ObjectNode m = JsonNodeFactory.instance.objectNode();
        m.put("data", i + "x".repeat(chars));
        return new Publication("/t", m, System.nanoTime());
    }

    @Test
    void aClientThatReadsNothingCostsAtMostItsByteBudget() {
        RecordingTransport t = new RecordingTransport();
        t.hold();
        Limits limits = Limits.DEFAULTS.withMaxClientBytes(64 * 1024).withMaxQueue(1000);
        Outbox o = new Outbox(t, limits, timer, "slow client");
        TopicQueue a = o.queue("/a");
        TopicQueue b = o.queue("/b");
        for (int i = 0; i < 10_000; i++) {
            o.offer(i % 2 == 0 ? a : b, message(i, 1000));
            assertTrue(o.queuedChars() <= limits.maxClientBytes(), "at most the budget waits, at message " + i);
        }
        assertTrue(o.dropped() > 9_000, "the rest was dropped: " + o.dropped());
        assertTrue(a.dropped() > 0 && b.dropped() > 0);
    }

    @Test
    void aFullQueueDropsItsOldest() throws Exception {
        RecordingTransport t = new RecordingTransport();
        t.hold();
        Outbox o = new Outbox(t, Limits.DEFAULTS.withMaxQueue(5), timer, "slow client");
        TopicQueue q = o.queue("/t");
        for (int i = 0; i < Outbox.MAX_IN_FLIGHT + 20; i++) {
            o.offer(q, message(i, 0));
        }
        t.release();
        assertEquals(Outbox.MAX_IN_FLIGHT + 5, t.drain().size(), "those on their way when the client stopped reading, and the newest 5");
        assertEquals(15, q.dropped());
    }

    @Test
    void repliesAreNeverDroppedButAClientThatLetsThemPileUpIsDisconnected() {
        RecordingTransport t = new RecordingTransport();
        t.hold();
        Limits limits = Limits.DEFAULTS;
        Outbox o = new Outbox(t, limits, timer, "deaf client");
        for (int i = 0; i < Outbox.MAX_IN_FLIGHT + limits.maxControlFrames(); i++) {
            o.reply("{\"op\":\"service_response\"}", null);
        }
        assertEquals(0, t.closedWith);
        o.reply("{\"op\":\"service_response\"}", null);
        assertEquals(Outbox.CLOSE_POLICY, t.closedWith);
    }

    @Test
    void aTransportThatCompletesAtOnceDoesNotDeepenTheStack() {
        RecordingTransport t = new RecordingTransport();
        Outbox o = new Outbox(t, Limits.DEFAULTS, timer, "fast client");
        t.hold();
        for (int i = 0; i <= 4_000; i++) { // below the limit on replies waiting
            o.reply("{\"n\":" + i + "}", null);
        }
        t.release();
        assertEquals(4_001, t.drain().size(), "every reply, sent from one drain loop without a stack overflow");
        assertEquals(4_001, o.sentFrames());
    }

    @Test
    void nothingIsSentAfterClose() {
        RecordingTransport t = new RecordingTransport();
        Outbox o = new Outbox(t, Limits.DEFAULTS, timer, "client");
        TopicQueue q = o.queue("/t");
        o.close();
        o.offer(q, message(1, 0));
        o.reply("{}", null);
        assertTrue(t.drain().isEmpty());
        assertEquals(0, o.queuedChars());
    }
}
