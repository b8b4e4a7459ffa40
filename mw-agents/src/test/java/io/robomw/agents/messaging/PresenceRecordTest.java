package io.robomw.agents.messaging;

import org.junit.jupiter.api.Test;

import java.nio.charset.StandardCharsets;
import java.time.Instant;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class PresenceRecordTest {

    private final PresenceRecord host = new PresenceRecord("ft host", true, Instant.parse("2026-11-24T10:15:30.123Z"),
            Instant.parse("2026-11-24T10:15:29.870Z"), "ft-1a2b", 3600,
            List.of("mqtt://127.0.0.1:1883/robomw", "tcp://127.0.0.1:7000"), "ft host", "rmi://127.0.0.1:1100/ft", List.of("ft-1"),
            List.of("3f2a Explorer RUNNING"));

    @Test
    void encodesToTheDocumentedText() {
        assertEquals("""
                robomw-presence 2
                node ft host
                status online
                time 2026-11-24T10:15:30.123Z
                since 2026-11-24T10:15:29.870Z
                client ft-1a2b
                session-expiry 3600
                messaging mqtt://127.0.0.1:1883/robomw
                messaging tcp://127.0.0.1:7000
                host ft host rmi://127.0.0.1:1100/ft
                robot ft-1
                agent 3f2a Explorer RUNNING
                """, new String(host.encode(), StandardCharsets.UTF_8));
    }

    @Test
    void decodesWhatItEncodes() {
        assertEquals(host, PresenceRecord.decode(host.encode(), "test"));
        PresenceRecord off = host.offline(Instant.parse("2026-11-24T11:00:00Z"));
        assertFalse(PresenceRecord.decode(off.encode(), "test").online());
    }

    @Test
    void refusesOtherVersionsUnknownKeysAndMissingFieldsNamingWhere() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> PresenceRecord.decode("robomw-presence 3\nnode x\n".getBytes(StandardCharsets.UTF_8), "robomw/presence/x"));
        assertTrue(e.getMessage().contains("robomw/presence/x") && e.getMessage().contains("version 1 or 2"), e.getMessage());
        e = assertThrows(IllegalArgumentException.class, () -> PresenceRecord.decode(
                "robomw-presence 1\nnode x\nstatus online\ntime 2026-11-24T10:15:30Z\nclient c\nsession-expiry 0\ncolour red\n".getBytes(StandardCharsets.UTF_8), "p"));
        assertTrue(e.getMessage().contains("line 7") && e.getMessage().contains("colour"), e.getMessage());
        e = assertThrows(IllegalArgumentException.class, () -> PresenceRecord.decode("robomw-presence 1\nnode x\n".getBytes(StandardCharsets.UTF_8), "p"));
        assertTrue(e.getMessage().contains("needs"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> PresenceRecord.decode(new byte[PresenceRecord.MAX_BYTES + 1], "p"));
        assertThrows(IllegalArgumentException.class, () -> PresenceRecord.decode(new byte[]{(byte) 0xff, 0, 1}, "p"));
    }

    /** Issue 37: a reader with the cluster's seal takes only records signed with it. */
    @Test
    void aSealedReaderTakesOnlyRecordsSignedWithItsKey() {
        io.robomw.agents.messaging.security.PresenceSeal cluster = io.robomw.agents.messaging.security.PresenceSeal.of(new byte[32]);
        io.robomw.agents.messaging.security.PresenceSeal other = io.robomw.agents.messaging.security.PresenceSeal.of(new byte[] {1, 2, 3, 4, 5, 6, 7, 8,
                9, 10, 11, 12, 13, 14, 15, 16});
        byte[] signed = host.encode(cluster);
        assertTrue(new String(signed, StandardCharsets.UTF_8).endsWith("\n") && new String(signed, StandardCharsets.UTF_8).contains("\nsig "));
        assertEquals(host, PresenceRecord.decodeSealed(signed, "p", cluster).orElseThrow());
        assertEquals(host, PresenceRecord.decode(signed, "p"), "a reader without a seal reads it too");
        assertTrue(PresenceRecord.decodeSealed(host.encode(), "p", cluster).isEmpty(), "unsigned");
        assertTrue(PresenceRecord.decodeSealed(host.encode(other), "p", cluster).isEmpty(), "signed with another key");
        byte[] changed = new String(signed, StandardCharsets.UTF_8).replace("status online", "status offline").getBytes(StandardCharsets.UTF_8);
        assertTrue(PresenceRecord.decodeSealed(changed, "p", cluster).isEmpty(), "changed after signing");
        byte[] sigFirst = ("robomw-presence 2\nsig x\nnode x\nstatus online\ntime 2026-11-24T10:15:30Z\nclient c\nsession-expiry 0\n")
                .getBytes(StandardCharsets.UTF_8);
        assertThrows(IllegalArgumentException.class, () -> PresenceRecord.decode(sigFirst, "p"), "the signature comes last");
    }

    @Test
    void aVersionOneRecordWasMadeSinceItsOwnTime() {
        PresenceRecord old = PresenceRecord.decode(
                "robomw-presence 1\nnode x\nstatus online\ntime 2026-11-24T10:15:30Z\nclient c\nsession-expiry 0\n".getBytes(StandardCharsets.UTF_8), "p");
        assertEquals(Instant.parse("2026-11-24T10:15:30Z"), old.since());
    }

    @Test
    void aLineBreakInAValueIsRefused() {
        assertThrows(IllegalArgumentException.class, () -> new PresenceRecord("a\nstatus offline", true, Instant.now(), Instant.now(), "", 0, List.of(), null, null,
                List.of(), List.of()));
    }
}
