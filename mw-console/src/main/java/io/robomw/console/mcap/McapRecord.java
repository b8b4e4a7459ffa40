package io.robomw.console.mcap;

import java.util.List;
import java.util.Map;

/**
 * One MCAP record, as {@link McapReader} reads it and {@link McapWriter} writes it. Unsigned 32-bit
 * fields are {@code long}s; CRCs are the 32 bits as an {@code int} (0 = not computed); times are
 * nanoseconds since the epoch the file chose (RoboMW: the Unix epoch).
 */
public sealed interface McapRecord {

    /** @return the record's opcode ({@link Mcap}) */
    int opcode();

    /** @param profile the profile ("" for none) @param library the writer */
    record Header(String profile, String library) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_HEADER;
        }
    }

    /** @param summaryStart offset of the summary, 0 if none @param summaryOffsetStart offset of the summary offsets, 0 if none @param summaryCrc CRC32 of the summary through this record's second field */
    record Footer(long summaryStart, long summaryOffsetStart, int summaryCrc) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_FOOTER;
        }
    }

    /** @param id 1.. @param name the schema's name @param encoding the schema's encoding ("jsonschema") @param data the schema */
    record Schema(int id, String name, String encoding, byte[] data) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_SCHEMA;
        }
    }

    /** @param id the channel @param schemaId its schema, 0 for none @param topic the topic @param messageEncoding "json" @param metadata free key/values */
    record Channel(int id, int schemaId, String topic, String messageEncoding, Map<String, String> metadata) implements McapRecord {
        /** Copies the map, keeping its order. */
        public Channel {
            metadata = java.util.Collections.unmodifiableMap(new java.util.LinkedHashMap<>(metadata));
        }

        @Override
        public int opcode() {
            return Mcap.OP_CHANNEL;
        }
    }

    /** @param channelId the channel @param sequence u32 counter @param logTime when recorded @param publishTime when published @param data the message */
    record Message(int channelId, long sequence, long logTime, long publishTime, byte[] data) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_MESSAGE;
        }
    }

    /** A chunk as stored; {@link McapReader} normally yields the records inside instead. */
    record Chunk(long messageStartTime, long messageEndTime, long uncompressedSize, int uncompressedCrc, String compression, byte[] records)
            implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_CHUNK;
        }
    }

    /** @param channelId the channel @param logTimes each message's log time @param offsets each message's offset in the uncompressed chunk */
    record MessageIndex(int channelId, long[] logTimes, long[] offsets) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_MESSAGE_INDEX;
        }
    }

    /** Where a chunk and its message indexes are. */
    record ChunkIndex(long messageStartTime, long messageEndTime, long chunkStartOffset, long chunkLength, Map<Integer, Long> messageIndexOffsets,
                      long messageIndexLength, String compression, long compressedSize, long uncompressedSize) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_CHUNK_INDEX;
        }
    }

    /** An auxiliary file. @param crc CRC32 of the fields before it, 0 = not computed */
    record Attachment(long logTime, long createTime, String name, String mediaType, byte[] data, int crc) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_ATTACHMENT;
        }
    }

    /** Where an attachment is. */
    record AttachmentIndex(long offset, long length, long logTime, long createTime, long dataSize, String name, String mediaType)
            implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_ATTACHMENT_INDEX;
        }
    }

    /** Counts over the whole file. */
    record Statistics(long messageCount, int schemaCount, long channelCount, long attachmentCount, long metadataCount, long chunkCount,
                      long messageStartTime, long messageEndTime, Map<Integer, Long> channelMessageCounts) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_STATISTICS;
        }
    }

    /** @param name the metadata's name @param metadata key/values */
    record Metadata(String name, Map<String, String> metadata) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_METADATA;
        }
    }

    /** Where a metadata record is. */
    record MetadataIndex(long offset, long length, String name) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_METADATA_INDEX;
        }
    }

    /** Where a group of summary records of one opcode is. */
    record SummaryOffset(int groupOpcode, long groupStart, long groupLength) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_SUMMARY_OFFSET;
        }
    }

    /** @param dataSectionCrc CRC32 of every byte before this record, 0 = not computed */
    record DataEnd(int dataSectionCrc) implements McapRecord {
        @Override
        public int opcode() {
            return Mcap.OP_DATA_END;
        }
    }

    /** A record this reader does not know (a newer format's, or an application's private 0x80-0xFF). */
    record Unknown(int opcode, byte[] content) implements McapRecord {
    }

    /** @return the record types a summary may hold, in the order {@link McapWriter} writes their groups */
    static List<Integer> summaryGroupOrder() {
        return List.of(Mcap.OP_SCHEMA, Mcap.OP_CHANNEL, Mcap.OP_STATISTICS, Mcap.OP_METADATA_INDEX, Mcap.OP_ATTACHMENT_INDEX, Mcap.OP_CHUNK_INDEX);
    }
}
