package io.robomw.agents.host.home;

import io.robomw.agents.host.DeliveryPolicy;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.stream.IntStream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** How arrivals go to a home: together when they queue behind a call, in order with reliable events, none lost or repeated. */
class HomeEventsTest {

    private static final String HOME = "rmi://127.0.0.1:1/home";
    private static final Duration WITHIN = Duration.ofSeconds(30);

    /** What the home was sent, one entry per call: its events' ids and kinds. */
    private final List<List<String>> calls = new CopyOnWriteArrayList<>();
    /** Holds the first call until released, so that the rest queue behind it. */
    private final CountDownLatch release = new CountDownLatch(1);
    private final CountDownLatch firstCallMade = new CountDownLatch(1);
    private HomeEvents events;

    private final HomeEvents.Sender sender = new HomeEvents.Sender() {
        @Override
        public void deliver(String home, AgentEvent event) throws Exception {
            sent(List.of(event));
        }

        @Override
        public void deliverArrivals(String home, List<AgentEvent> arrivals) throws Exception {
            sent(arrivals);
        }

        private void sent(List<AgentEvent> list) throws InterruptedException {
            calls.add(list.stream().map(e -> e.kind() + " " + e.id() + " at " + e.location()).toList());
            firstCallMade.countDown();
            assertTrue(release.await(60, TimeUnit.SECONDS), "released within 60 s");
        }
    };

    @AfterEach
    void close() {
        release.countDown();
        if (events != null) {
            events.close();
        }
    }

    private HomeEvents events() {
        events = new HomeEvents("h", DeliveryPolicy.defaults(), sender, (e, delivered) -> { }, FailurePolicy.logging());
        return events;
    }

    private static AgentEvent arrival(UUID id, String where) {
        return new AgentEvent(id, 0, AgentEvent.Kind.ARRIVED, where, new byte[0]);
    }

    private static String arrived(UUID id, String where) {
        return "ARRIVED " + id + " at " + where;
    }

    @Test
    void arrivalsQueuedBehindACallGoTogetherInTheNextInTheOrderMade() throws Exception {
        HomeEvents e = events();
        UUID first = UUID.randomUUID();
        e.arrived(HOME, arrival(first, "a"));
        assertTrue(firstCallMade.await(30, TimeUnit.SECONDS), "the first arrival is sent at once, alone");
        List<UUID> ids = IntStream.range(0, 50).mapToObj(i -> UUID.randomUUID()).toList();
        ids.forEach(id -> e.arrived(HOME, arrival(id, "b")));
        release.countDown();
        Await.until("every arrival sent", WITHIN, () -> calls.stream().mapToInt(List::size).sum() == 51, calls::toString);
        assertEquals(List.of(arrived(first, "a")), calls.get(0));
        assertEquals(2, calls.size(), "the 50 that queued behind the first call went in one: " + calls);
        assertEquals(ids.stream().map(id -> arrived(id, "b")).toList(), calls.get(1));
    }

    @Test
    void aNewerArrivalOfTheSameAgentMakesTheQueuedOneMootAndNoCallCarriesMoreThanTheMost() throws Exception {
        HomeEvents e = events();
        e.arrived(HOME, arrival(UUID.randomUUID(), "a"));
        assertTrue(firstCallMade.await(30, TimeUnit.SECONDS));
        int n = HomeEvents.MAX_ARRIVALS_PER_CALL + 10;
        List<UUID> ids = IntStream.range(0, n).mapToObj(i -> UUID.randomUUID()).toList();
        ids.forEach(id -> e.arrived(HOME, arrival(id, "b")));
        UUID mover = ids.get(3);
        e.arrived(HOME, arrival(mover, "c"));
        release.countDown();
        Await.until("every arrival sent", WITHIN, () -> calls.stream().mapToInt(List::size).sum() == 1 + n, calls::toString);
        List<String> after = new ArrayList<>();
        for (List<String> call : calls.subList(1, calls.size())) {
            assertTrue(call.size() <= HomeEvents.MAX_ARRIVALS_PER_CALL, "a call of " + call.size());
            after.addAll(call);
        }
        List<String> expected = new ArrayList<>(ids.stream().filter(id -> !id.equals(mover)).map(id -> arrived(id, "b")).toList());
        expected.add(arrived(mover, "c"));
        assertEquals(expected, after, "the moot arrival at b is not sent, the newer one at c is, once, and none is lost");
    }

    @Test
    void aReportQueuedBetweenArrivalsKeepsItsPlace() throws Exception {
        HomeEvents e = events();
        e.arrived(HOME, arrival(UUID.randomUUID(), "a"));
        assertTrue(firstCallMade.await(30, TimeUnit.SECONDS));
        UUID x = UUID.randomUUID();
        UUID y = UUID.randomUUID();
        UUID z = UUID.randomUUID();
        e.arrived(HOME, arrival(x, "b"));
        e.arrived(HOME, arrival(y, "b"));
        e.owe(HOME, new AgentEvent(y, 1, AgentEvent.Kind.REPORT, "b", new byte[] {1}), System.currentTimeMillis());
        e.arrived(HOME, arrival(z, "b"));
        release.countDown();
        Await.until("every event sent", WITHIN, () -> calls.size() == 4, calls::toString);
        assertEquals(List.of(arrived(x, "b"), arrived(y, "b")), calls.get(1));
        assertEquals(List.of("REPORT " + y + " at b"), calls.get(2));
        assertEquals(List.of(arrived(z, "b")), calls.get(3));
        assertTrue(e.awaitDelivered(y, 10_000), "the report is no longer owed");
    }
}
