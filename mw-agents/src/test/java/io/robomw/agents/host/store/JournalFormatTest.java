package io.robomw.agents.host.store;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.zip.CRC32C;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The journal's format as {@link JournalStore}'s javadoc gives it, written out here again: its
 * header (magic and version), the code of every record type, and what is refused when opened (an
 * unknown version, no header, an unknown record type), naming the file.
 */
class JournalFormatTest {

    private static final byte[] HEADER_V1 = {(byte) 0x89, 'R', 'M', 'J', 0, 0, 0, 1};
    private static final byte[] HEADER_V2 = {(byte) 0x89, 'R', 'M', 'J', 0, 0, 0, 2};
    /** The header of the version written now. */
    private static final byte[] HEADER = {(byte) 0x89, 'R', 'M', 'J', 0, 0, 0, 4};
    private static final UUID ID = UUID.fromString("00000000-0000-0001-0000-000000000002");

    @TempDir
    Path dir;

    @Test
    void aJournalBeginsWithItsHeaderAndEveryRecordCarriesItsTypeCode() throws Exception {
        Path store = dir.resolve("s");
        JournalStore s = JournalStore.open(store);
        s.accepted(ID, 3, new byte[] {1, 2}, 0, 2);
        s.started(ID, 3);
        s.departing(ID, 4, new byte[] {5}, 0, 1);
        s.departed(ID, 4);
        s.eventPending(new AgentStore.PendingEvent(ID, 1, 1_700_000_000_000L, new byte[] {9}));
        s.eventDelivered(ID, 1);
        UUID large = new UUID(9, 9);
        s.departing(large, 1, new byte[JournalStore.SPOOL_MIN_BYTES], 0, JournalStore.SPOOL_MIN_BYTES);
        s.departed(large, 1);
        byte[] file = Files.readAllBytes(store.resolve("journal"));
        assertArrayEquals(HEADER, java.util.Arrays.copyOf(file, 8));
        assertEquals(List.of(1, 2, 3, 4, 5, 6, 9, 4), typesOf(file, 8),
                "ACCEPTED, STARTED, DEPARTING, DEPARTED, EVENT_PENDING, EVENT_DELIVERED, DEPARTING_SPOOLED, DEPARTED");
        s.close();

        JournalStore compacted = JournalStore.open(store); // rewrites what is live: the hop seen
        compacted.close();
        byte[] rewritten = Files.readAllBytes(store.resolve("journal"));
        assertArrayEquals(HEADER, java.util.Arrays.copyOf(rewritten, 8));
        assertEquals(List.of(7), typesOf(rewritten, 8), "SEEN");
        try (JournalStore again = JournalStore.open(store)) {
            assertEquals(3, again.highestHop(ID));
        }
    }

    @Test
    void aJournalOfAnotherFormatVersionIsRefusedNamingTheFileAndTheVersion() throws Exception {
        Path journal = journal(new byte[] {(byte) 0x89, 'R', 'M', 'J', 0, 0, 0, 5}, record(1, ID, 1, new byte[] {1}));
        IOException e = assertThrows(IOException.class, () -> JournalStore.open(journal.getParent()));
        assertTrue(e.getMessage().contains(journal.toString()) && e.getMessage().contains("format version 5"), e.getMessage());
        assertEquals(8 + record(1, ID, 1, new byte[] {1}).length, Files.size(journal), "left as it was");
    }

    @Test
    void aJournalWithARecordOfAnUnknownTypeIsRefusedNamingTheFileTheCodeAndWhereItIs() throws Exception {
        byte[] first = record(1, ID, 1, new byte[] {1});
        Path journal = journal(HEADER_V1, first, record(99, ID, 1, null));
        IOException e = assertThrows(IOException.class, () -> JournalStore.open(journal.getParent()));
        assertTrue(e.getMessage().contains(journal.toString()) && e.getMessage().contains("unknown record type code 99")
                && e.getMessage().contains("at byte " + (8 + first.length)), e.getMessage());
    }

    @Test
    void aRefusedJournalLeavesItsDirectoryFreeForTheNextOpen() throws Exception {
        Path journal = journal(new byte[] {(byte) 0x89, 'R', 'M', 'J', 0, 0, 0, 5});
        assertThrows(IOException.class, () -> JournalStore.open(journal.getParent()));
        IOException again = assertThrows(IOException.class, () -> JournalStore.open(journal.getParent()));
        assertTrue(again.getMessage().contains("format version 5"), "refused for its version again, not for a lock it left held: " + again.getMessage());
        Files.write(journal, HEADER);
        JournalStore.open(journal.getParent()).close();
    }

    @Test
    void aSecondStoreOnADirectoryThisProcessHoldsIsRefusedClearly() throws Exception {
        Path store = dir.resolve("held");
        try (JournalStore first = JournalStore.open(store)) {
            IOException e = assertThrows(IOException.class, () -> JournalStore.open(store));
            assertTrue(e.getMessage().contains("is in use by another host"), e.getMessage());
        }
    }

    @Test
    void aFileWithoutAHeaderThatIsNoJournalIsRefusedNamingTheFile() throws Exception {
        Path journal = journal("these are not the records you are looking for".getBytes(StandardCharsets.US_ASCII));
        IOException e = assertThrows(IOException.class, () -> JournalStore.open(journal.getParent()));
        assertTrue(e.getMessage().contains(journal.toString()) && e.getMessage().contains("has no format header"), e.getMessage());
    }

    @Test
    void aJournalWrittenBeforeTheHeaderExistedIsReadAsVersion1AndGetsTheHeader() throws Exception {
        Path journal = journal(record(1, ID, 5, new byte[] {4, 2}), record(5, ID, 1, new byte[] {7}));
        JournalStore s = JournalStore.open(journal.getParent());
        assertEquals(1, s.recoveredAgents().size());
        assertArrayEquals(new byte[] {4, 2}, s.recoveredAgents().get(0).image());
        assertEquals(1, s.recoveredEvents().size());
        assertEquals(5, s.highestHop(ID));
        s.close();
        assertArrayEquals(HEADER, java.util.Arrays.copyOf(Files.readAllBytes(journal), 8));
    }

    @Test
    void aVersion1JournalIsReadAndRewrittenInTheCurrentVersion() throws Exception {
        Path journal = journal(HEADER_V1, record(1, ID, 5, new byte[] {4, 2}), record(2, ID, 5, null));
        JournalStore s = JournalStore.open(journal.getParent());
        assertEquals(AgentStore.Phase.STARTED, s.recoveredAgents().get(0).phase());
        s.close();
        assertArrayEquals(HEADER, java.util.Arrays.copyOf(Files.readAllBytes(journal), 8));
    }

    @Test
    void anAgentsNextEventNumberSurvivesItsEventsBeingDeliveredAndTheJournalCompacted() throws Exception {
        Path store = dir.resolve("seq");
        JournalStore s = JournalStore.open(store);
        s.accepted(ID, 2, new byte[] {1}, 0, 1);
        s.started(ID, 2);
        for (long seq = 4; seq <= 6; seq++) {
            s.eventPending(new AgentStore.PendingEvent(ID, seq, 1_700_000_000_000L, new byte[] {(byte) seq}));
            s.eventDelivered(ID, seq);
        }
        assertEquals(7, s.nextEventSeq(ID));
        s.close();
        JournalStore replayed = JournalStore.open(store); // replays the EVENT_PENDING records, then compacts: an EVENT_SEQ record
        assertEquals(7, replayed.nextEventSeq(ID));
        replayed.close();
        byte[] compacted = Files.readAllBytes(store.resolve("journal"));
        assertEquals(List.of(7, 1, 2, 8), typesOf(compacted, 8), "SEEN, ACCEPTED, STARTED, EVENT_SEQ");
        try (JournalStore again = JournalStore.open(store)) {
            assertEquals(7, again.nextEventSeq(ID));
            again.departed(ID, 3);
            assertEquals(0, again.nextEventSeq(ID), "an agent that left numbers its events from its image again");
        }
    }

    @Test
    void aDepartedRecordForgetsOnlyTheCopyThatLeftNotOneThatCameWithThatHopOrLater() throws Exception {
        Path store = dir.resolve("same-host");
        UUID sameHost = new UUID(3, 1);
        UUID cameBack = new UUID(3, 2);
        UUID ended = new UUID(3, 3);
        try (JournalStore s = JournalStore.open(store)) {
            // A hop to this same host: the new copy is stored (hop 4) before the old one, departing with hop 4, is recorded departed.
            s.accepted(sameHost, 3, new byte[] {1}, 0, 1);
            s.started(sameHost, 3);
            s.departing(sameHost, 4, new byte[] {2}, 0, 1);
            s.accepted(sameHost, 4, new byte[] {3}, 0, 1);
            s.departed(sameHost, 4);
            // Gone to another host and back (hop 5) before the sender recorded hop 4 departed.
            s.accepted(cameBack, 3, new byte[] {1}, 0, 1);
            s.departing(cameBack, 4, new byte[] {2}, 0, 1);
            s.accepted(cameBack, 5, new byte[] {4}, 0, 1);
            s.departed(cameBack, 4);
            // Ended here, after a departure that failed.
            s.accepted(ended, 3, new byte[] {1}, 0, 1);
            s.departing(ended, 4, new byte[] {2}, 0, 1);
            s.departed(ended, 4);
        }
        try (JournalStore replayed = JournalStore.open(store)) {
            assertEquals(List.of(new UUID(3, 1) + " 4 ACCEPTED [3]", new UUID(3, 2) + " 5 ACCEPTED [4]"), held(replayed));
        }
        try (JournalStore compacted = JournalStore.open(store)) { // what the first open rewrote
            assertEquals(List.of(new UUID(3, 1) + " 4 ACCEPTED [3]", new UUID(3, 2) + " 5 ACCEPTED [4]"), held(compacted));
        }
    }

    @Test
    void aDepartedRecordOfAVersion2JournalForgetsTheAgentWhateverCopyIsHeld() throws Exception {
        Path journal = journal(HEADER_V2, record(1, ID, 5, new byte[] {4, 2}), record(4, ID, 0, null));
        try (JournalStore s = JournalStore.open(journal.getParent())) {
            assertTrue(s.recoveredAgents().isEmpty(), "version 2's DEPARTED (number 0) forgets the agent: " + held(s));
            assertEquals(5, s.highestHop(ID));
        }
    }

    private static List<String> held(JournalStore s) {
        return s.recoveredAgents().stream().map(a -> a.id() + " " + a.hop() + " " + a.phase() + " " + java.util.Arrays.toString(a.image())).toList();
    }

    @Test
    void theStoreRemembersTheHopsOfABoundedNumberOfAgentsButNeverForgetsOneItHolds() throws Exception {
        Path store = dir.resolve("bounded");
        UUID held = new UUID(9, 9);
        List<UUID> gone = new ArrayList<>();
        try (JournalStore s = JournalStore.open(store, 3)) {
            s.accepted(held, 1, new byte[] {1}, 0, 1);
            for (int i = 0; i < 5; i++) {
                UUID id = new UUID(1, i);
                gone.add(id);
                s.accepted(id, 7, new byte[] {1}, 0, 1);
                s.departed(id, 8);
            }
            assertEquals(1, s.highestHop(held), "an agent held here is never forgotten");
            assertEquals(-1, s.highestHop(gone.get(0)), "the agent seen longest ago is forgotten");
            assertEquals(7, s.highestHop(gone.get(4)));
        }
        try (JournalStore again = JournalStore.open(store, 3)) {
            assertEquals(1, again.highestHop(held));
            assertEquals(7, again.highestHop(gone.get(4)));
            assertEquals(-1, again.highestHop(gone.get(0)), "compaction writes only what is remembered");
        }
    }

    @Test
    void aJournalWrittenBeforeTheHeaderExistedHoldingOnlyZerosIsEmpty() throws Exception {
        Path journal = journal(new byte[4096]);
        JournalStore s = JournalStore.open(journal.getParent());
        assertTrue(s.recoveredAgents().isEmpty());
        s.close();
        assertArrayEquals(HEADER, Files.readAllBytes(journal));
    }

    @Test
    void aHostDoesNotStartOnAStoredAgentWhoseImageHasAnUnknownKindAndNamesTheJournal() throws Exception {
        byte[] image = new byte[64];
        image[0] = 0x0E; // kind code 14: no such kind
        Path journal = journal(HEADER_V1, record(1, ID, 1, image));
        IOException e = assertThrows(IOException.class,
                () -> AgentHost.builder("resumer").clusterKey(ClusterKey.fromPassphrase("k")).store(journal.getParent()).start());
        assertTrue(e.getMessage().contains(journal.toString()) && e.getMessage().contains("unknown agent image kind code 14")
                && e.getMessage().contains(ID.toString()), e.getMessage());
    }

    /** A record as the class javadoc lays it out. */
    private static byte[] record(int type, UUID id, long number, byte[] data) {
        int payload = 1 + 16 + 8 + (data == null ? 0 : 4 + data.length);
        ByteBuffer b = ByteBuffer.allocate(4 + payload + 4);
        b.putInt(payload).put((byte) type).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).putLong(number);
        if (data != null) {
            b.putInt(data.length).put(data);
        }
        CRC32C crc = new CRC32C();
        crc.update(b.array(), 4, payload);
        return b.putInt((int) crc.getValue()).array();
    }

    private Path journal(byte[]... parts) throws IOException {
        Path store = dir.resolve("store");
        Files.createDirectories(store);
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        for (byte[] p : parts) {
            out.write(p);
        }
        return Files.write(store.resolve("journal"), out.toByteArray());
    }

    /** The type codes of the records from {@code at} on, until the zeros. */
    private static List<Integer> typesOf(byte[] file, int at) {
        List<Integer> types = new ArrayList<>();
        ByteBuffer b = ByteBuffer.wrap(file);
        while (at + 4 <= file.length && b.getInt(at) != 0) {
            int payload = b.getInt(at);
            types.add(file[at + 4] & 0xFF);
            at += 4 + payload + 4;
        }
        return types;
    }
}
