package io.robomw.platform.link;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Clock;
import java.time.Instant;
import java.time.ZoneOffset;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;

class WireLogTest {

    private static final Clock FIXED = Clock.fixed(Instant.parse("2026-11-21T19:05:01.123456789Z"), ZoneOffset.UTC);

    @TempDir
    Path tempDir;

    @Test
    void shouldWriteSentAndReceivedLinesWithMicrosecondUtcTimestamps() throws IOException {
        Path file = tempDir.resolve("wire.log");
        try (WireLog log = WireLog.open(file, FIXED)) {
            log.sent(TestBytes.hex("FF 0C 00 00 04 EE"), 1, 4);
            log.received(new byte[] {0x02, 0x00, 0x00}, 0, 3);
            log.note("link lost: serial /dev/pts/5");
        }

        assertEquals(List.of(
                "2026-11-21T19:05:01.123456Z > 0C 00 00 04",
                "2026-11-21T19:05:01.123456Z < 02 00 00",
                "2026-11-21T19:05:01.123456Z # link lost: serial /dev/pts/5"), Files.readAllLines(file));
    }

    @Test
    void shouldAppendToExistingFile() throws IOException {
        Path file = tempDir.resolve("wire.log");
        Files.writeString(file, "earlier line\n");
        try (WireLog log = WireLog.open(file, FIXED)) {
            log.sent(new byte[] {0x01}, 0, 1);
        }

        assertEquals(List.of("earlier line", "2026-11-21T19:05:01.123456Z > 01"), Files.readAllLines(file));
    }

    @Test
    void shouldFlushEachLineBeforeClose() throws IOException {
        Path file = tempDir.resolve("wire.log");
        try (WireLog log = WireLog.open(file, FIXED)) {
            log.received(new byte[] {0x7F}, 0, 1);

            assertEquals(List.of("2026-11-21T19:05:01.123456Z < 7F"), Files.readAllLines(file));
        }
    }
}
