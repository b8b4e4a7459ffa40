package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.security.ReplayStore;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Path;
import java.time.Instant;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Issue 37: a signed presence captured earlier and published again at the broker is not believed, across a reader's restart too. */
class PresenceWindowTest {

    private static final String BROKER = "127.0.0.1:1883/robomw";
    private static final Instant FIRST = Instant.parse("2026-11-24T10:00:00Z");
    private static final Instant SECOND = Instant.parse("2026-11-24T11:00:00Z");

    @TempDir
    Path dir;

    private static PresenceRecord online(Instant since, Instant time) {
        return new PresenceRecord("h", true, time, since, "mw-h-1", 0, List.of("mqtt://127.0.0.1:1883/robomw"), "h", "rmi://127.0.0.1:1100/h",
                List.of(), List.of());
    }

    @Test
    void aRecordOfAnEarlierConnectionIsRefusedOnceALaterOneWasTaken() {
        PresenceWindow w = new PresenceWindow(BROKER, ReplayStore.memoryOnly());
        PresenceRecord oldOffline = online(FIRST, FIRST).offline(FIRST);
        assertTrue(w.take("mw-h-1", online(FIRST, FIRST.plusSeconds(1)), 0));
        assertTrue(w.take("mw-h-1", oldOffline, 0), "the will of the connection taken comes when it ends");
        assertTrue(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(1)), 0), "the host came back");
        assertFalse(w.take("mw-h-1", oldOffline, 0), "its old will, replayed, would mark it offline");
        assertFalse(w.take("mw-h-1", online(FIRST, FIRST.plusSeconds(5)), 0), "nor may an old announcement bring back its old address");
    }

    @Test
    void anOlderOnlineRecordOfTheSameConnectionIsRefusedButItsWillIsTaken() {
        PresenceWindow w = new PresenceWindow(BROKER, ReplayStore.memoryOnly());
        assertTrue(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(10)), 0));
        assertFalse(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(5)), 0));
        assertTrue(w.take("mw-h-1", online(SECOND, SECOND).offline(SECOND), 0), "the will carries the connection's start as its time");
        assertTrue(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(20)), 0), "and the host may come back on the same session");
    }

    @Test
    void aReaderThatRestartsStillRefusesRecordsOfConnectionsOlderThanTheNewestItTook() {
        Path f = dir.resolve("reader.presence.replay");
        long now = System.currentTimeMillis();
        try (ReplayStore s = ReplayStore.in(f, PresenceWindow.KEEP)) {
            PresenceWindow w = new PresenceWindow(BROKER, s);
            assertTrue(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(1)), now));
            assertTrue(w.take("mw-h-1", online(SECOND, SECOND).offline(SECOND.plusSeconds(60)), now), "it closed");
        }
        try (ReplayStore s = ReplayStore.in(f, PresenceWindow.KEEP)) {
            PresenceWindow w = new PresenceWindow(BROKER, s);
            assertFalse(w.take("mw-h-1", online(FIRST, FIRST).offline(FIRST), now), "an earlier connection's");
            assertFalse(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(1)), now), "the last connection's online, from before it closed");
            assertTrue(w.take("mw-h-1", online(SECOND, SECOND.plusSeconds(90)), now), "it came back on the same session");
            assertTrue(w.take("mw-h-2", online(FIRST, FIRST), now), "another client has a window of its own");
        }
        try (ReplayStore s = ReplayStore.in(f, PresenceWindow.KEEP)) {
            assertTrue(new PresenceWindow("127.0.0.1:1884/robomw", s).take("mw-h-1", online(FIRST, FIRST), now),
                    "the same client id at another broker is another client");
        }
    }
}
