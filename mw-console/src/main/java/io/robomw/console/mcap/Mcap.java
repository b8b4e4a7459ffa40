package io.robomw.console.mcap;

/**
 * The MCAP container format (version 0), as its specification (mcap.dev/spec) lays it out. Every
 * integer is little-endian.
 *
 * <pre>
 * file    := MAGIC Header DataSection [Summary] [SummaryOffsets] Footer MAGIC
 * record  := opcode:u8  length:u64  content[length]
 *
 *  offset 0          1                  9
 *         +----------+------------------+--------------------------+
 *         | opcode   | content length   | content ...              |
 *         +----------+------------------+--------------------------+
 *
 * String  := length:u32 utf8[length]           Bytes32 := length:u32 bytes[length]
 * Map     := byteLength:u32 (key value)*       Timestamp := u64 nanoseconds
 * </pre>
 *
 * <p>Opcodes (0x01-0x7F belong to the format, 0x80-0xFF to applications, 0x00 is never valid):
 *
 * <table>
 *   <caption>MCAP record opcodes</caption>
 *   <tr><th>opcode</th><th>record</th><th>where</th></tr>
 *   <tr><td>0x01</td><td>Header</td><td>first record</td></tr>
 *   <tr><td>0x02</td><td>Footer</td><td>last record</td></tr>
 *   <tr><td>0x03</td><td>Schema</td><td>data (or in chunks), summary</td></tr>
 *   <tr><td>0x04</td><td>Channel</td><td>data (or in chunks), summary</td></tr>
 *   <tr><td>0x05</td><td>Message</td><td>data, in chunks</td></tr>
 *   <tr><td>0x06</td><td>Chunk</td><td>data</td></tr>
 *   <tr><td>0x07</td><td>Message Index</td><td>data, after its chunk</td></tr>
 *   <tr><td>0x08</td><td>Chunk Index</td><td>summary</td></tr>
 *   <tr><td>0x09</td><td>Attachment</td><td>data</td></tr>
 *   <tr><td>0x0A</td><td>Attachment Index</td><td>summary</td></tr>
 *   <tr><td>0x0B</td><td>Statistics</td><td>summary</td></tr>
 *   <tr><td>0x0C</td><td>Metadata</td><td>data</td></tr>
 *   <tr><td>0x0D</td><td>Metadata Index</td><td>summary</td></tr>
 *   <tr><td>0x0E</td><td>Summary Offset</td><td>summary offset section</td></tr>
 *   <tr><td>0x0F</td><td>Data End</td><td>last record of the data section</td></tr>
 * </table>
 */
public final class Mcap {

    /** {@code 0x89 'M' 'C' 'A' 'P' '0' '\r' '\n'}: the first and last eight bytes; {@code '0'} is the major version. */
    public static final byte[] MAGIC = {(byte) 0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
    /** Bytes before a record's content: the opcode and the u64 content length. */
    public static final int RECORD_PREFIX_LENGTH = 1 + 8;

    /** Header record. */
    public static final int OP_HEADER = 0x01;
    /** Footer record. */
    public static final int OP_FOOTER = 0x02;
    /** Schema record. */
    public static final int OP_SCHEMA = 0x03;
    /** Channel record. */
    public static final int OP_CHANNEL = 0x04;
    /** Message record. */
    public static final int OP_MESSAGE = 0x05;
    /** Chunk record. */
    public static final int OP_CHUNK = 0x06;
    /** Message Index record. */
    public static final int OP_MESSAGE_INDEX = 0x07;
    /** Chunk Index record. */
    public static final int OP_CHUNK_INDEX = 0x08;
    /** Attachment record. */
    public static final int OP_ATTACHMENT = 0x09;
    /** Attachment Index record. */
    public static final int OP_ATTACHMENT_INDEX = 0x0A;
    /** Statistics record. */
    public static final int OP_STATISTICS = 0x0B;
    /** Metadata record. */
    public static final int OP_METADATA = 0x0C;
    /** Metadata Index record. */
    public static final int OP_METADATA_INDEX = 0x0D;
    /** Summary Offset record. */
    public static final int OP_SUMMARY_OFFSET = 0x0E;
    /** Data End record. */
    public static final int OP_DATA_END = 0x0F;

    /** Fixed content length of a Footer: summary_start u64, summary_offset_start u64, summary_crc u32. */
    public static final int FOOTER_CONTENT_LENGTH = 8 + 8 + 4;

    private Mcap() {
    }

    /**
     * @param opcode an opcode
     * @return the record's name, for messages
     */
    public static String recordName(int opcode) {
        return switch (opcode) {
            case OP_HEADER -> "Header";
            case OP_FOOTER -> "Footer";
            case OP_SCHEMA -> "Schema";
            case OP_CHANNEL -> "Channel";
            case OP_MESSAGE -> "Message";
            case OP_CHUNK -> "Chunk";
            case OP_MESSAGE_INDEX -> "Message Index";
            case OP_CHUNK_INDEX -> "Chunk Index";
            case OP_ATTACHMENT -> "Attachment";
            case OP_ATTACHMENT_INDEX -> "Attachment Index";
            case OP_STATISTICS -> "Statistics";
            case OP_METADATA -> "Metadata";
            case OP_METADATA_INDEX -> "Metadata Index";
            case OP_SUMMARY_OFFSET -> "Summary Offset";
            case OP_DATA_END -> "Data End";
            default -> String.format("record 0x%02X", opcode);
        };
    }
}
