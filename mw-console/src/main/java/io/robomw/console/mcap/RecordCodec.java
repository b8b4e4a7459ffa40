package io.robomw.console.mcap;

import io.robomw.console.mcap.McapRecord.Attachment;
import io.robomw.console.mcap.McapRecord.AttachmentIndex;
import io.robomw.console.mcap.McapRecord.Channel;
import io.robomw.console.mcap.McapRecord.Chunk;
import io.robomw.console.mcap.McapRecord.ChunkIndex;
import io.robomw.console.mcap.McapRecord.DataEnd;
import io.robomw.console.mcap.McapRecord.Footer;
import io.robomw.console.mcap.McapRecord.Header;
import io.robomw.console.mcap.McapRecord.Message;
import io.robomw.console.mcap.McapRecord.MessageIndex;
import io.robomw.console.mcap.McapRecord.Metadata;
import io.robomw.console.mcap.McapRecord.MetadataIndex;
import io.robomw.console.mcap.McapRecord.Schema;
import io.robomw.console.mcap.McapRecord.Statistics;
import io.robomw.console.mcap.McapRecord.SummaryOffset;
import io.robomw.console.mcap.McapRecord.Unknown;

import java.util.zip.CRC32;

/**
 * Writes and reads the content of each record, field by field, in the order the specification's
 * tables give. A reader ignores bytes after the fields it knows (the specification lets records
 * grow at the end), except in Message, Data End and Footer, which cannot grow and whose data runs
 * to the end.
 */
final class RecordCodec {

    private RecordCodec() {
    }

    /**
     * Appends {@code opcode length content}.
     *
     * @return the record's whole length, prefix included
     */
    static long write(McapRecord r, LeWriter out) {
        int start = out.length();
        out.u8(r.opcode()).u64(0);
        int contentStart = out.length();
        if (r instanceof Header h) {
            out.string(h.profile()).string(h.library());
        } else if (r instanceof Footer f) {
            out.u64(f.summaryStart()).u64(f.summaryOffsetStart()).u32(Integer.toUnsignedLong(f.summaryCrc()));
        } else if (r instanceof Schema s) {
            out.u16(s.id()).string(s.name()).string(s.encoding()).bytes32(s.data());
        } else if (r instanceof Channel c) {
            out.u16(c.id()).u16(c.schemaId()).string(c.topic()).string(c.messageEncoding()).stringMap(c.metadata());
        } else if (r instanceof Message m) {
            out.u16(m.channelId()).u32(m.sequence()).u64(m.logTime()).u64(m.publishTime()).raw(m.data());
        } else if (r instanceof Chunk c) {
            out.u64(c.messageStartTime()).u64(c.messageEndTime()).u64(c.uncompressedSize()).u32(Integer.toUnsignedLong(c.uncompressedCrc()))
                    .string(c.compression()).u64(c.records().length).raw(c.records());
        } else if (r instanceof MessageIndex m) {
            out.u16(m.channelId()).u32(m.logTimes().length * 16L);
            for (int i = 0; i < m.logTimes().length; i++) {
                out.u64(m.logTimes()[i]).u64(m.offsets()[i]);
            }
        } else if (r instanceof ChunkIndex c) {
            out.u64(c.messageStartTime()).u64(c.messageEndTime()).u64(c.chunkStartOffset()).u64(c.chunkLength())
                    .u16u64Map(c.messageIndexOffsets()).u64(c.messageIndexLength()).string(c.compression()).u64(c.compressedSize())
                    .u64(c.uncompressedSize());
        } else if (r instanceof Attachment a) {
            out.u64(a.logTime()).u64(a.createTime()).string(a.name()).string(a.mediaType()).u64(a.data().length).raw(a.data());
            CRC32 crc = new CRC32();
            crc.update(out.array(), contentStart, out.length() - contentStart);
            out.u32(crc.getValue());
        } else if (r instanceof AttachmentIndex a) {
            out.u64(a.offset()).u64(a.length()).u64(a.logTime()).u64(a.createTime()).u64(a.dataSize()).string(a.name()).string(a.mediaType());
        } else if (r instanceof Statistics s) {
            out.u64(s.messageCount()).u16(s.schemaCount()).u32(s.channelCount()).u32(s.attachmentCount()).u32(s.metadataCount())
                    .u32(s.chunkCount()).u64(s.messageStartTime()).u64(s.messageEndTime()).u16u64Map(s.channelMessageCounts());
        } else if (r instanceof Metadata m) {
            out.string(m.name()).stringMap(m.metadata());
        } else if (r instanceof MetadataIndex m) {
            out.u64(m.offset()).u64(m.length()).string(m.name());
        } else if (r instanceof SummaryOffset s) {
            out.u8(s.groupOpcode()).u64(s.groupStart()).u64(s.groupLength());
        } else if (r instanceof DataEnd d) {
            out.u32(Integer.toUnsignedLong(d.dataSectionCrc()));
        } else if (r instanceof Unknown u) {
            out.raw(u.content());
        }
        out.u64At(start + 1, out.length() - contentStart);
        return out.length() - start;
    }

    /**
     * Reads one record's content.
     *
     * @param opcode the record's opcode
     * @param bytes  holds the content
     * @param offset where it starts
     * @param length its length
     * @param where  for messages: the record and its offset in the source
     * @return the record
     * @throws McapFormatException if a field does not fit or is not valid
     */
    static McapRecord read(int opcode, byte[] bytes, int offset, int length, String where) throws McapFormatException {
        LeReader in = new LeReader(bytes, offset, length, where);
        return switch (opcode) {
            case Mcap.OP_HEADER -> new Header(in.string("profile"), in.string("library"));
            case Mcap.OP_FOOTER -> {
                if (length != Mcap.FOOTER_CONTENT_LENGTH) {
                    throw new McapFormatException(where + ": a Footer is " + Mcap.FOOTER_CONTENT_LENGTH + " bytes long, this one " + length);
                }
                yield new Footer(in.u64("summary_start"), in.u64("summary_offset_start"), (int) in.u32("summary_crc"));
            }
            case Mcap.OP_SCHEMA -> new Schema(in.u16("id"), in.string("name"), in.string("encoding"), in.bytes32("data"));
            case Mcap.OP_CHANNEL -> new Channel(in.u16("id"), in.u16("schema_id"), in.string("topic"), in.string("message_encoding"),
                    in.stringMap("metadata"));
            case Mcap.OP_MESSAGE -> new Message(in.u16("channel_id"), in.u32("sequence"), in.u64("log_time"), in.u64("publish_time"), in.rest());
            case Mcap.OP_CHUNK -> new Chunk(in.u64("message_start_time"), in.u64("message_end_time"), in.u64("uncompressed_size"),
                    (int) in.u32("uncompressed_crc"), in.string("compression"), in.bytes64("records"));
            case Mcap.OP_MESSAGE_INDEX -> {
                int channel = in.u16("channel_id");
                long n = in.u32("records length");
                if (n % 16 != 0 || n > in.remaining()) {
                    throw new McapFormatException(where + ": field records is " + n + " bytes, not a whole number of 16-byte (log_time, offset) entries"
                            + " within the " + in.remaining() + " bytes left");
                }
                long[] times = new long[(int) (n / 16)];
                long[] offsets = new long[times.length];
                for (int i = 0; i < times.length; i++) {
                    times[i] = in.u64("log_time");
                    offsets[i] = in.u64("offset");
                }
                yield new MessageIndex(channel, times, offsets);
            }
            case Mcap.OP_CHUNK_INDEX -> new ChunkIndex(in.u64("message_start_time"), in.u64("message_end_time"), in.u64("chunk_start_offset"),
                    in.u64("chunk_length"), in.u16u64Map("message_index_offsets"), in.u64("message_index_length"), in.string("compression"),
                    in.u64("compressed_size"), in.u64("uncompressed_size"));
            case Mcap.OP_ATTACHMENT -> {
                long logTime = in.u64("log_time");
                long createTime = in.u64("create_time");
                String name = in.string("name");
                String mediaType = in.string("media_type");
                byte[] data = in.bytes64("data");
                int crcEnd = in.position();
                int crc = (int) in.u32("crc");
                if (crc != 0) {
                    CRC32 c = new CRC32();
                    c.update(bytes, offset, crcEnd - offset);
                    if ((int) c.getValue() != crc) {
                        throw new McapFormatException(where + ": attachment '" + name + "' fails its CRC (stored " + Integer.toUnsignedString(crc)
                                + ", computed " + c.getValue() + "): the file is damaged");
                    }
                }
                yield new Attachment(logTime, createTime, name, mediaType, data, crc);
            }
            case Mcap.OP_ATTACHMENT_INDEX -> new AttachmentIndex(in.u64("offset"), in.u64("length"), in.u64("log_time"), in.u64("create_time"),
                    in.u64("data_size"), in.string("name"), in.string("media_type"));
            case Mcap.OP_STATISTICS -> new Statistics(in.u64("message_count"), in.u16("schema_count"), in.u32("channel_count"),
                    in.u32("attachment_count"), in.u32("metadata_count"), in.u32("chunk_count"), in.u64("message_start_time"),
                    in.u64("message_end_time"), in.u16u64Map("channel_message_counts"));
            case Mcap.OP_METADATA -> new Metadata(in.string("name"), in.stringMap("metadata"));
            case Mcap.OP_METADATA_INDEX -> new MetadataIndex(in.u64("offset"), in.u64("length"), in.string("name"));
            case Mcap.OP_SUMMARY_OFFSET -> new SummaryOffset(in.u8("group_opcode"), in.u64("group_start"), in.u64("group_length"));
            case Mcap.OP_DATA_END -> new DataEnd((int) in.u32("data_section_crc"));
            default -> {
                if (opcode == 0) {
                    throw new McapFormatException(where + ": opcode 0x00 is not a record (the file is damaged, or this is not MCAP)");
                }
                yield new Unknown(opcode, in.rest());
            }
        };
    }
}
