package io.robomw.agents.host.store;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

class JournalStoreTest {

    @TempDir
    Path dir;

    @Test
    void recordsSurviveAKillThatLeavesTheZeroFilledTailAndACloseThatCutsIt() throws Exception {
        UUID started = UUID.randomUUID();
        UUID departing = UUID.randomUUID();
        UUID gone = UUID.randomUUID();
        Path live = dir.resolve("live");
        JournalStore store = JournalStore.open(live);
        accept(store, started, 3, new byte[] {1, 2, 3});
        store.started(started, 3);
        accept(store, departing, 1, new byte[] {4});
        store.departing(departing, 2, new byte[] {0, 5, 6, 0}, 1, 2);
        accept(store, gone, 7, new byte[300_000]); // larger than a preallocation step holds ahead
        store.departed(gone, 8);
        store.eventPending(new AgentStore.PendingEvent(started, 1, 1_700_000_000_123L, new byte[] {9}));
        long withZeros = Files.size(live.resolve("journal"));
        assertTrue(withZeros >= 4 << 20, "the journal is grown ahead of its records: " + withZeros);

        // A kill: the files as they are, zero-filled tail and all (copied, as this JVM holds the lock).
        Path killed = dir.resolve("killed");
        Files.createDirectories(killed);
        Files.copy(live.resolve("journal"), killed.resolve("journal"));
        JournalStore afterKill = JournalStore.open(killed);
        assertRecovered(afterKill, started, departing, gone);
        afterKill.close();

        store.close();
        assertTrue(Files.size(live.resolve("journal")) < withZeros, "close cuts the zeros off");
        JournalStore reopened = JournalStore.open(live);
        assertRecovered(reopened, started, departing, gone);
        accept(reopened, UUID.randomUUID(), 1, new byte[] {7}); // appends after the recovered records
        reopened.close();
    }

    private static void accept(AgentStore s, UUID id, long hop, byte[] image) throws Exception {
        byte[] framed = new byte[image.length + 3];
        System.arraycopy(image, 0, framed, 2, image.length);
        s.accepted(id, hop, framed, 2, image.length);
    }

    private static void assertRecovered(JournalStore s, UUID started, UUID departing, UUID gone) {
        List<AgentStore.StoredAgent> agents = s.recoveredAgents();
        assertEquals(2, agents.size(), agents.toString());
        AgentStore.StoredAgent a = agents.stream().filter(x -> x.id().equals(started)).findFirst().orElseThrow();
        assertEquals(AgentStore.Phase.STARTED, a.phase());
        assertArrayEquals(new byte[] {1, 2, 3}, a.image());
        AgentStore.StoredAgent d = agents.stream().filter(x -> x.id().equals(departing)).findFirst().orElseThrow();
        assertEquals(AgentStore.Phase.DEPARTING, d.phase());
        assertEquals(2, d.hop());
        assertArrayEquals(new byte[] {5, 6}, d.image());
        assertEquals(7, s.highestHop(gone));
        assertEquals(1, s.recoveredEvents().size());
        assertEquals(1_700_000_000_123L, s.recoveredEvents().get(0).owedSince(), "an owed event keeps its age across restarts");
        assertArrayEquals(new byte[] {9}, s.recoveredEvents().get(0).event());
    }
}
