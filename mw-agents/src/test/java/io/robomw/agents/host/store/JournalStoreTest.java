package io.robomw.agents.host.store;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
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

    @Test
    void anAgentStoredAndMarkedStartedAtOnceTakesOneForcedWriteAndResumesAsStarted() throws Exception {
        UUID id = UUID.randomUUID();
        JournalStore store = JournalStore.open(dir.resolve("s"));
        long before = store.forces();
        store.acceptedStarting(id, 4, new byte[] {0, 7, 8, 9}, 1, 3);
        assertEquals(before + 1, store.forces(), "the agent and its started mark are forced together, once");
        store.accepted(UUID.randomUUID(), 1, new byte[] {1}, 0, 1);
        store.started(id, 4);
        assertEquals(before + 3, store.forces(), "accepted and started apart force once each");
        store.close();
        try (JournalStore reopened = JournalStore.open(dir.resolve("s"))) {
            AgentStore.StoredAgent a = reopened.recoveredAgents().stream().filter(x -> x.id().equals(id)).findFirst().orElseThrow();
            assertEquals(AgentStore.Phase.STARTED, a.phase(), "its stop counts as begun: not run again after a restart");
            assertEquals(4, a.hop());
            assertArrayEquals(new byte[] {7, 8, 9}, a.image());
            assertEquals(4, reopened.highestHop(id));
        }
    }

    @Test
    void aHopsStateIsInTheJournalOnceWrittenFromTheCallersArrayAndSurvivesCompaction() throws Exception {
        // Random bytes: a pattern that occurs in the journal only where the store wrote it.
        byte[] state = new byte[64 * 1024];
        new java.util.Random(21).nextBytes(state);
        byte[] frame = new byte[state.length + 40];
        System.arraycopy(state, 0, frame, 17, state.length);
        UUID held = UUID.randomUUID();
        Path d = dir.resolve("once");
        JournalStore store = JournalStore.open(d);
        store.acceptedStarting(held, 1, frame, 17, state.length);
        java.util.Arrays.fill(frame, (byte) 0); // the caller reuses its array: the store kept no reference to it
        assertEquals(1, occurrences(Files.readAllBytes(d.resolve("journal")), state), "the state is written to the journal once");
        // Grow the journal past the compaction threshold with agents that come and go: the held
        // agent's image is read back from the journal into the compacted one (the store keeps no copy).
        byte[] big = new byte[JournalStore.SPOOL_MIN_BYTES - 1]; // in the journal, not spooled
        for (int i = 0; i < (36 << 20) / big.length; i++) {
            UUID other = UUID.randomUUID();
            store.departing(other, 1, big, 0, big.length);
            store.departed(other, 1);
        }
        assertTrue(Files.size(d.resolve("journal")) < 20 << 20, "the journal was compacted (36 MiB went through it): " + Files.size(d.resolve("journal")));
        assertEquals(1, occurrences(Files.readAllBytes(d.resolve("journal")), state), "compaction kept the held agent's state, once");
        store.close();
        try (JournalStore reopened = JournalStore.open(d)) {
            assertEquals(1, reopened.recoveredAgents().size());
            AgentStore.StoredAgent a = reopened.recoveredAgents().get(0);
            assertEquals(held, a.id());
            assertEquals(AgentStore.Phase.STARTED, a.phase());
            assertArrayEquals(state, a.image());
        }
    }

    @Test
    void aLargeDepartingImageGoesToASpoolFileThatAKillKeepsAndThatIsDeletedOnceTheAgentHasLeft() throws Exception {
        byte[] arrived = new byte[JournalStore.SPOOL_MIN_BYTES];
        byte[] leaving = new byte[JournalStore.SPOOL_MIN_BYTES + 100];
        java.util.Random random = new java.util.Random(5);
        random.nextBytes(arrived);
        random.nextBytes(leaving);
        UUID id = UUID.randomUUID();
        Path d = dir.resolve("spool");
        JournalStore store = JournalStore.open(d);
        store.acceptedStarting(id, 1, arrived, 0, arrived.length);
        store.departing(id, 2, leaving, 0, leaving.length);
        Path spooled = d.resolve("departing").resolve(id + "-2");
        assertEquals(0, occurrences(Files.readAllBytes(d.resolve("journal")), leaving), "the image it leaves with is not in the journal");
        assertArrayEquals(leaving, Files.readAllBytes(spooled), "it is in its spool file");

        // A kill before the next host acknowledged: the files as they are.
        Path killed = copy(d, "killed");
        try (JournalStore afterKill = JournalStore.open(killed)) {
            AgentStore.StoredAgent a = afterKill.recoveredAgents().get(0);
            assertEquals(AgentStore.Phase.DEPARTING, a.phase(), "sent again, as it left");
            assertEquals(2, a.hop());
            assertArrayEquals(leaving, a.image());
        }
        // A power cut that lost the spool file (it is never forced): the agent resumes from the state it arrived with.
        Path cut = copy(d, "cut");
        Files.delete(cut.resolve("departing").resolve(id + "-2"));
        try (JournalStore afterCut = JournalStore.open(cut)) {
            AgentStore.StoredAgent a = afterCut.recoveredAgents().get(0);
            assertEquals(AgentStore.Phase.STARTED, a.phase(), "its stop counts as begun: it goes on, the stop recorded as interrupted");
            assertEquals(1, a.hop());
            assertArrayEquals(arrived, a.image());
        }

        store.departed(id, 2);
        assertFalse(Files.exists(spooled), "the next host has it: its spool file is deleted");
        store.close();
        try (JournalStore reopened = JournalStore.open(d)) {
            assertTrue(reopened.recoveredAgents().isEmpty());
        }
    }

    /** @return a copy of a store's directory, as a kill leaves it (this JVM holds the original's lock) */
    private Path copy(Path from, String name) throws Exception {
        Path to = dir.resolve(name);
        Files.createDirectories(to.resolve("departing"));
        Files.copy(from.resolve("journal"), to.resolve("journal"));
        try (java.util.stream.Stream<Path> files = Files.list(from.resolve("departing"))) {
            for (Path f : (Iterable<Path>) files::iterator) {
                Files.copy(f, to.resolve("departing").resolve(f.getFileName().toString()));
            }
        }
        return to;
    }

    /** @return how many times {@code pattern} occurs in {@code in} (a naive scan on its first 16 bytes, then a full compare) */
    private static int occurrences(byte[] in, byte[] pattern) {
        int n = 0;
        for (int i = 0; i + pattern.length <= in.length; i++) {
            if (java.util.Arrays.equals(in, i, i + 16, pattern, 0, 16) && java.util.Arrays.equals(in, i, i + pattern.length, pattern, 0, pattern.length)) {
                n++;
            }
        }
        return n;
    }

    @Test
    void theSameArchiveBroughtByManyAgentsAtOnceIsStoredOnceAndNoneIsRefused() throws Exception {
        byte[] code = new byte[256 * 1024];
        new java.util.Random(3).nextBytes(code);
        io.robomw.agents.host.code.CodeArchive archive = io.robomw.agents.host.code.CodeArchive.of(code);
        try (JournalStore s = JournalStore.open(dir)) {
            java.util.concurrent.ExecutorService writers = java.util.concurrent.Executors.newFixedThreadPool(8);
            try {
                java.util.concurrent.CountDownLatch go = new java.util.concurrent.CountDownLatch(1);
                List<java.util.concurrent.Future<?>> puts = new java.util.ArrayList<>();
                for (int i = 0; i < 8; i++) {
                    puts.add(writers.submit(() -> {
                        go.await();
                        s.putArchive(archive);
                        return null;
                    }));
                }
                go.countDown();
                for (java.util.concurrent.Future<?> p : puts) {
                    p.get(30, java.util.concurrent.TimeUnit.SECONDS);
                }
            } finally {
                writers.shutdownNow();
            }
        }
        try (var files = Files.list(dir.resolve("archives"))) {
            assertEquals(List.of(archive.digest().hex() + ".jar"), files.map(f -> f.getFileName().toString()).toList(), "one archive, no leftovers");
        }
        try (JournalStore again = JournalStore.open(dir)) {
            assertArrayEquals(code, again.archive(archive.digest()).orElseThrow().bytes());
        }
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
