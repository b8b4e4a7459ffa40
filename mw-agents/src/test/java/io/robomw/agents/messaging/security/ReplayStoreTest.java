package io.robomw.agents.messaging.security;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The replay window kept on disk: what a node took before a restart is known after it, within the time it matters. */
class ReplayStoreTest {

    private static final Duration KEEP = Duration.ofMinutes(10);

    @TempDir
    Path dir;

    @Test
    void theHighestNumberTakenFromEachSourceIsKnownAfterARestart() {
        Path f = dir.resolve("node.replay");
        long now = System.currentTimeMillis();
        try (ReplayStore s = ReplayStore.in(f, KEEP)) {
            assertEquals(Long.MIN_VALUE, s.floor(7));
            s.record(7, 10, now);
            s.record(7, 12, now);
            s.record(7, 11, now);
            s.record(-3, 1, now);
            assertEquals(Long.MIN_VALUE, s.floor(7), "within a run the window in memory decides; the floor is what came before this start");
        }
        try (ReplayStore s = ReplayStore.in(f, KEEP)) {
            assertEquals(12, s.floor(7));
            assertEquals(1, s.floor(-3));
            assertEquals(Long.MIN_VALUE, s.floor(8));
        }
    }

    @Test
    void sourcesLastSeenLongerAgoThanItMattersAreForgotten() {
        Path f = dir.resolve("node.replay");
        try (ReplayStore s = ReplayStore.in(f, KEEP)) {
            s.record(7, 10, System.currentTimeMillis() - KEEP.toMillis() - 1000);
            s.record(8, 10, System.currentTimeMillis());
        }
        try (ReplayStore s = ReplayStore.in(f, KEEP)) {
            assertEquals(Long.MIN_VALUE, s.floor(7), "its frames are stale anyway");
            assertEquals(10, s.floor(8));
        }
    }

    @Test
    void aSecondStoreOnTheSameFileKeepsItsWindowInMemoryOnly() {
        Path f = dir.resolve("node.replay");
        try (ReplayStore first = ReplayStore.in(f, KEEP); ReplayStore second = ReplayStore.in(f, KEEP)) {
            first.record(1, 5, System.currentTimeMillis());
            second.record(2, 5, System.currentTimeMillis());
        }
        try (ReplayStore s = ReplayStore.in(f, KEEP)) {
            assertEquals(5, s.floor(1));
            assertEquals(Long.MIN_VALUE, s.floor(2), "the second never held the file");
        }
    }

    @Test
    void aFileOfAnotherVersionIsNotReadAndNothingIsRefusedBecauseOfIt() throws IOException {
        Path f = dir.resolve("node.replay");
        byte[] other = new byte[ReplayStore.HEADER + ReplayStore.SLOTS * ReplayStore.SLOT];
        System.arraycopy(ReplayStore.MAGIC, 0, other, 0, 4);
        other[5] = 9;
        Files.write(f, other);
        try (ReplayStore s = ReplayStore.in(f, KEEP)) {
            assertEquals(Long.MIN_VALUE, s.floor(1));
            s.record(1, 1, System.currentTimeMillis());
        }
        assertEquals(9, Files.readAllBytes(f)[5], "the file is left as it was, for whoever wrote it");
    }

    @Test
    void namesBecomePlainFileNames() {
        assertEquals("host-a.replay", ReplayStore.fileFor(dir, "host-a").getFileName().toString());
        String odd = ReplayStore.fileFor(dir, "../../etc/passwd").getFileName().toString();
        assertTrue(odd.matches("[A-Za-z0-9._-]+-[0-9a-f]{8}\\.replay") && !odd.contains("/"), odd);
        assertEquals(dir, ReplayStore.fileFor(dir, "../../etc/passwd").getParent());
    }
}
