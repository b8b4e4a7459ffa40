package io.robomw.console.mcap;

import org.junit.jupiter.api.Test;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Map;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Round trips through {@link McapWriter} and {@link McapReader}, and the reader on damaged and hostile bytes. */
class McapReaderTest {

    private static byte[] recording(int messages, long chunkSize) throws IOException {
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        try (McapWriter w = new McapWriter(bytes, McapWriter.Options.INDEXED.withChunkSize(chunkSize))) {
            w.start("", "robomw-test");
            int schema = w.registerSchema("foxglove.PoseInFrame", "jsonschema", "{}".getBytes(StandardCharsets.UTF_8));
            int[] channels = {w.registerChannel(schema, "/robots/a/pose", "json", Map.of()), w.registerChannel(schema, "/robots/b/pose", "json", Map.of()),
                    w.registerChannel(0, "/log", "json", Map.of("k", "v"))};
            for (int i = 0; i < messages; i++) {
                w.addMessage(channels[i % 3], i, 1_000L * i, 1_000L * i, ("{\"i\":" + i + "}").getBytes(StandardCharsets.UTF_8));
            }
            w.addAttachment(5, 0, "world.yaml", "application/yaml", "name: arena".getBytes(StandardCharsets.UTF_8));
            w.addMetadata("run", Map.of("robomw", "0.1.0"));
        }
        return bytes.toByteArray();
    }

    private static List<McapRecord> readAll(byte[] file, McapReader.Options options) throws IOException {
        List<McapRecord> out = new ArrayList<>();
        try (McapReader r = new McapReader(new ByteArrayInputStream(file), "test.mcap", options)) {
            for (McapRecord x; (x = r.next()) != null; ) {
                out.add(x);
            }
        }
        return out;
    }

    @Test
    void messagesComeBackInOrderAcrossManyChunksWithTheirIndexesAndStatistics() throws IOException {
        List<McapRecord> records = readAll(recording(1000, 2048), McapReader.Options.DEFAULT);
        List<McapRecord.Message> messages = records.stream().filter(McapRecord.Message.class::isInstance).map(McapRecord.Message.class::cast).toList();
        assertEquals(1000, messages.size());
        for (int i = 0; i < 1000; i++) {
            assertEquals(1_000L * i, messages.get(i).logTime());
            assertEquals("{\"i\":" + i + "}", new String(messages.get(i).data(), StandardCharsets.UTF_8));
        }
        McapRecord.Statistics stats = records.stream().filter(McapRecord.Statistics.class::isInstance).map(McapRecord.Statistics.class::cast)
                .findFirst().orElseThrow();
        assertEquals(1000, stats.messageCount());
        assertTrue(stats.chunkCount() > 10, "2 KiB chunks: " + stats.chunkCount());
        long chunkIndexes = records.stream().filter(McapRecord.ChunkIndex.class::isInstance).count();
        assertEquals(stats.chunkCount(), chunkIndexes);
        assertEquals(1, records.stream().filter(McapRecord.Attachment.class::isInstance).count());
        assertInstanceOf(McapRecord.Footer.class, records.get(records.size() - 1));
    }

    @Test
    void theChunkIndexPointsAtItsChunkAndTheMessageIndexAtEachMessage() throws IOException {
        byte[] file = recording(30, 1 << 20);
        List<McapRecord> records = readAll(file, McapReader.Options.DEFAULT.keepChunks());
        McapRecord.ChunkIndex index = records.stream().filter(McapRecord.ChunkIndex.class::isInstance).map(McapRecord.ChunkIndex.class::cast)
                .findFirst().orElseThrow();
        assertEquals(Mcap.OP_CHUNK, file[(int) index.chunkStartOffset()]);
        McapRecord.Chunk chunk = (McapRecord.Chunk) records.stream().filter(McapRecord.Chunk.class::isInstance).findFirst().orElseThrow();
        McapRecord.MessageIndex mi = records.stream().filter(McapRecord.MessageIndex.class::isInstance).map(McapRecord.MessageIndex.class::cast)
                .findFirst().orElseThrow();
        assertEquals(10, mi.offsets().length);
        for (long offset : mi.offsets()) {
            assertEquals(Mcap.OP_MESSAGE, chunk.records()[(int) offset], "message index offset " + offset);
        }
        assertEquals(Mcap.OP_MESSAGE_INDEX, file[(int) (long) index.messageIndexOffsets().get(mi.channelId())]);
    }

    @Test
    void fieldsAddedToARecordByANewerWriterAreIgnored() throws IOException {
        LeWriter b = new LeWriter(256);
        b.raw(Mcap.MAGIC);
        RecordCodec.write(new McapRecord.Header("", "newer"), b);
        int schemaStart = b.length();
        RecordCodec.write(new McapRecord.Schema(1, "s", "jsonschema", new byte[] {1}), b);
        b.raw(new byte[] {9, 9, 9}); // three bytes of a field this reader does not know
        b.u64At(schemaStart + 1, b.length() - schemaStart - Mcap.RECORD_PREFIX_LENGTH);
        RecordCodec.write(new McapRecord.DataEnd(0), b);
        RecordCodec.write(new McapRecord.Footer(0, 0, 0), b);
        b.raw(Mcap.MAGIC);
        List<McapRecord> records = readAll(b.toByteArray(), McapReader.Options.DEFAULT);
        McapRecord.Schema s = (McapRecord.Schema) records.get(1);
        assertEquals("s", s.name());
        assertArrayEquals(new byte[] {1}, s.data());
    }

    private static String failure(byte[] file) {
        return assertThrows(McapFormatException.class, () -> readAll(file, McapReader.Options.DEFAULT)).getMessage();
    }

    @Test
    void aFileThatIsNotMcapIsRefusedByItsFirstBytes() {
        String m = failure("%PDF-1.7 not a recording".getBytes(StandardCharsets.US_ASCII));
        assertTrue(m.contains("test.mcap") && m.contains("not an MCAP file"), m);
        assertTrue(failure(new byte[0]).contains("empty"));
    }

    @Test
    void anotherMajorVersionIsNamed() throws IOException {
        byte[] file = recording(3, 1 << 20);
        file[5] = '1';
        assertTrue(failure(file).contains("major version '1'"), failure(file));
    }

    @Test
    void aRecordLongerThanTheLimitIsRefusedBeforeAnythingIsAllocated() throws IOException {
        byte[] file = recording(3, 1 << 20);
        // The header's length field: claim 2^62 bytes.
        Arrays.fill(file, 9, 17, (byte) 0);
        file[16] = 0x40;
        String m = failure(file);
        assertTrue(m.contains("Header record at offset 8") && m.contains("the limit is"), m);
    }

    @Test
    void aStringRunningPastItsRecordNamesTheField() throws IOException {
        LeWriter b = new LeWriter(64);
        b.raw(Mcap.MAGIC);
        b.u8(Mcap.OP_HEADER).u64(8).u32(1000).u32(0); // profile claims 1000 bytes, the record has 4
        byte[] file = b.toByteArray();
        String m = failure(file);
        assertTrue(m.contains("profile") && m.contains("1000"), m);
    }

    @Test
    void aDamagedChunkFailsItsCrc() throws IOException {
        byte[] file = recording(30, 1 << 20);
        List<McapRecord> records = readAll(file, McapReader.Options.DEFAULT.keepChunks());
        McapRecord.ChunkIndex index = (McapRecord.ChunkIndex) records.stream().filter(McapRecord.ChunkIndex.class::isInstance).findFirst().orElseThrow();
        file[(int) (index.chunkStartOffset() + index.chunkLength() - 5)] ^= 0x20; // inside the last message's JSON
        String m = failure(file);
        assertTrue(m.contains("Chunk record") && m.contains("fails its CRC"), m);
    }

    @Test
    void aCompressedChunkIsAClearErrorNotGarbage() throws IOException {
        LeWriter b = new LeWriter(64);
        b.raw(Mcap.MAGIC);
        RecordCodec.write(new McapRecord.Header("", ""), b);
        RecordCodec.write(new McapRecord.Chunk(0, 0, 3, 0, "zstd", new byte[] {1, 2, 3}), b);
        String m = failure(b.toByteArray());
        assertTrue(m.contains("compressed with 'zstd'"), m);
    }

    @Test
    void aTruncatedRecordingIsAnErrorOrEndsQuietlyAfterItsLastWholeRecord() throws IOException {
        byte[] whole = recording(300, 1024);
        int cut = whole.length / 2;
        byte[] file = Arrays.copyOf(whole, cut);
        assertTrue(failure(file).contains("truncated"), failure(file));
        List<McapRecord> records = new ArrayList<>();
        try (McapReader r = new McapReader(new ByteArrayInputStream(file), "cut.mcap", McapReader.Options.DEFAULT.tolerant())) {
            for (McapRecord x; (x = r.next()) != null; ) {
                records.add(x);
            }
            assertTrue(r.truncated());
        }
        long messages = records.stream().filter(McapRecord.Message.class::isInstance).count();
        assertTrue(messages > 50 && messages < 300, messages + " messages before the cut");
    }

    @Test
    void bytesAfterTheClosingMagicAreRefused() throws IOException {
        byte[] whole = recording(3, 1 << 20);
        byte[] file = Arrays.copyOf(whole, whole.length + 1);
        assertTrue(failure(file).contains("after the closing magic"));
    }

    @Test
    void opcodeZeroIsNotARecord() {
        LeWriter b = new LeWriter(64);
        b.raw(Mcap.MAGIC);
        RecordCodec.write(new McapRecord.Header("", ""), b);
        b.u8(0).u64(0);
        assertTrue(failure(b.toByteArray()).contains("opcode 0x00"));
    }

    @Test
    void aPrivateRecordIsPassedOnAsUnknown() throws IOException {
        LeWriter b = new LeWriter(64);
        b.raw(Mcap.MAGIC);
        RecordCodec.write(new McapRecord.Header("", ""), b);
        b.u8(0x80).u64(2).u8(7).u8(8);
        RecordCodec.write(new McapRecord.DataEnd(0), b);
        RecordCodec.write(new McapRecord.Footer(0, 0, 0), b);
        b.raw(Mcap.MAGIC);
        List<McapRecord> records = readAll(b.toByteArray(), McapReader.Options.DEFAULT);
        McapRecord.Unknown u = assertInstanceOf(McapRecord.Unknown.class, records.get(1));
        assertEquals(0x80, u.opcode());
        assertArrayEquals(new byte[] {7, 8}, u.content());
    }
}
