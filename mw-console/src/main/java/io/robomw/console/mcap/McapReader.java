package io.robomw.console.mcap;

import io.robomw.console.mcap.McapRecord.Chunk;
import io.robomw.console.mcap.McapRecord.DataEnd;
import io.robomw.console.mcap.McapRecord.Footer;

import java.io.IOException;
import java.io.InputStream;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.zip.CRC32;

/**
 * Reads an MCAP file from start to end as a stream of records, with the records inside each chunk
 * in place of the chunk. Checks what the specification lets a reader check: the magic at both
 * ends, the header first and the footer last, every record's length against what is left, every
 * field's length against its record, UTF-8 strings, chunk, attachment, data-section and summary
 * CRCs (where the writer stored one), and chunk sizes. Bad bytes give a {@link McapFormatException}
 * naming the source, the offset and the record; nothing here trusts a length before checking it,
 * so a damaged or hostile file cannot make the reader allocate more than its limits.
 *
 * <p>Not thread-safe; one reader per stream.
 */
public final class McapReader implements AutoCloseable {

    /**
     * @param maxRecordBytes     the largest record accepted (a chunk included)
     * @param expandChunks       yield a chunk's records instead of the chunk
     * @param tolerateTruncation end quietly (with {@link #truncated()} true) where the file stops
     *                           early, after its last whole record (a recording whose writer was
     *                           killed), instead of failing
     */
    public record Options(long maxRecordBytes, boolean expandChunks, boolean tolerateTruncation) {
        /** 256 MiB records, chunks expanded, truncation an error. */
        public static final Options DEFAULT = new Options(256L << 20, true, false);

        /** @return these options, but ending quietly at a truncation */
        public Options tolerant() {
            return new Options(maxRecordBytes, expandChunks, true);
        }

        /** @return these options, but yielding chunks as they are */
        public Options keepChunks() {
            return new Options(maxRecordBytes, false, tolerateTruncation);
        }
    }

    private final InputStream in;
    private final String source;
    private final Options options;
    private final CRC32 dataCrc = new CRC32();
    private final CRC32 summaryCrc = new CRC32();
    private final Deque<McapRecord> pending = new ArrayDeque<>();
    private long offset;
    private boolean started;
    private boolean dataEnded;
    private boolean done;
    private boolean truncated;
    private long summaryStart = -1;

    /**
     * @param in      the file's bytes (closed with this reader)
     * @param source  the file's name, for messages
     * @param options limits and choices
     */
    public McapReader(InputStream in, String source, Options options) {
        this.in = in;
        this.source = source;
        this.options = options;
    }

    /** @return whether the file stopped early and {@link Options#tolerateTruncation()} let it */
    public boolean truncated() {
        return truncated;
    }

    /** @return the byte offset read up to */
    public long offset() {
        return offset;
    }

    /**
     * @return the next record, or {@code null} after the footer and the closing magic
     * @throws McapFormatException if the bytes are not MCAP
     * @throws IOException         if reading fails
     */
    public McapRecord next() throws IOException {
        if (!pending.isEmpty()) {
            return pending.poll();
        }
        if (done) {
            return null;
        }
        if (!started) {
            byte[] magic = new byte[Mcap.MAGIC.length];
            if (!readFully(magic)) {
                throw new McapFormatException(source + ": empty or shorter than the MCAP magic (" + offset + " bytes): not an MCAP file");
            }
            checkMagic(magic, "starts");
            dataCrc.update(magic);
            offset += magic.length;
            started = true;
        }
        long recordOffset = offset;
        byte[] prefix = new byte[Mcap.RECORD_PREFIX_LENGTH];
        if (!readFully(prefix)) {
            return truncatedAt(recordOffset, "before a record's opcode and length");
        }
        int opcode = prefix[0] & 0xFF;
        long length = 0;
        for (int i = 0; i < 8; i++) {
            length |= (long) (prefix[1 + i] & 0xFF) << (8 * i);
        }
        String where = source + ": " + Mcap.recordName(opcode) + " record at offset " + recordOffset;
        if (length < 0 || length > options.maxRecordBytes()) {
            throw new McapFormatException(where + " says it is " + Long.toUnsignedString(length) + " bytes long; the limit is "
                    + options.maxRecordBytes() + " (the file is damaged, or not MCAP)");
        }
        // readNBytes grows its buffer as bytes arrive: a damaged length costs no more memory than the file has bytes.
        byte[] content = in.readNBytes((int) length);
        if (content.length != length) {
            return truncatedAt(recordOffset, "inside " + Mcap.recordName(opcode) + " record of " + length + " bytes");
        }
        offset += prefix.length + length;
        if (recordOffset == Mcap.MAGIC.length && opcode != Mcap.OP_HEADER) {
            throw new McapFormatException(where + ": the first record must be a Header");
        }
        if (opcode == Mcap.OP_HEADER && recordOffset != Mcap.MAGIC.length) {
            throw new McapFormatException(where + ": a Header may only be the first record");
        }
        McapRecord r = RecordCodec.read(opcode, content, 0, content.length, where);
        if (r instanceof DataEnd d) {
            if (d.dataSectionCrc() != 0 && d.dataSectionCrc() != (int) dataCrc.getValue()) {
                throw new McapFormatException(where + ": the data section fails its CRC (stored " + Integer.toUnsignedString(d.dataSectionCrc())
                        + ", computed " + dataCrc.getValue() + "): the file is damaged");
            }
            dataEnded = true;
        } else if (!dataEnded) {
            dataCrc.update(prefix);
            dataCrc.update(content);
        }
        if (r instanceof Footer f) {
            checkFooter(f, prefix, content, where);
            byte[] magic = new byte[Mcap.MAGIC.length];
            if (!readFully(magic)) {
                return truncatedAt(offset, "in the closing magic");
            }
            checkMagic(magic, "ends");
            offset += magic.length;
            if (in.read() != -1) {
                throw new McapFormatException(source + ": bytes after the closing magic at offset " + offset);
            }
            done = true;
            return r;
        }
        if (dataEnded && !(r instanceof DataEnd)) {
            if (summaryStart < 0) {
                summaryStart = recordOffset;
            }
            summaryCrc.update(prefix);
            summaryCrc.update(content);
        }
        if (r instanceof Chunk c && options.expandChunks()) {
            expand(c, where);
            return next();
        }
        return r;
    }

    private void checkFooter(Footer f, byte[] prefix, byte[] content, String where) throws McapFormatException {
        if (f.summaryCrc() == 0) {
            return;
        }
        summaryCrc.update(prefix);
        summaryCrc.update(content, 0, content.length - 4);
        if ((int) summaryCrc.getValue() != f.summaryCrc()) {
            throw new McapFormatException(where + ": the summary fails its CRC (stored " + Integer.toUnsignedString(f.summaryCrc()) + ", computed "
                    + summaryCrc.getValue() + "): the file is damaged");
        }
    }

    private void expand(Chunk c, String where) throws McapFormatException {
        if (!c.compression().isEmpty()) {
            throw new McapFormatException(where + ": the chunk is compressed with '" + c.compression()
                    + "', which this reader does not read (RoboMW writes uncompressed chunks); write the file again without compression");
        }
        if (c.uncompressedSize() != c.records().length) {
            throw new McapFormatException(where + ": the chunk says it holds " + Long.toUnsignedString(c.uncompressedSize()) + " bytes but has "
                    + c.records().length);
        }
        if (c.uncompressedCrc() != 0) {
            CRC32 crc = new CRC32();
            crc.update(c.records());
            if ((int) crc.getValue() != c.uncompressedCrc()) {
                throw new McapFormatException(where + ": the chunk fails its CRC (stored " + Integer.toUnsignedString(c.uncompressedCrc())
                        + ", computed " + crc.getValue() + "): the file is damaged");
            }
        }
        byte[] b = c.records();
        int pos = 0;
        while (pos < b.length) {
            if (b.length - pos < Mcap.RECORD_PREFIX_LENGTH) {
                throw new McapFormatException(where + ": the chunk's last " + (b.length - pos) + " bytes are too few for a record");
            }
            int opcode = b[pos] & 0xFF;
            long length = 0;
            for (int i = 0; i < 8; i++) {
                length |= (long) (b[pos + 1 + i] & 0xFF) << (8 * i);
            }
            String inner = where + ", " + Mcap.recordName(opcode) + " record at chunk offset " + pos;
            if (length < 0 || length > b.length - pos - Mcap.RECORD_PREFIX_LENGTH) {
                throw new McapFormatException(inner + " says it is " + Long.toUnsignedString(length) + " bytes long but the chunk has "
                        + (b.length - pos - Mcap.RECORD_PREFIX_LENGTH) + " left");
            }
            if (opcode == Mcap.OP_CHUNK || opcode == Mcap.OP_HEADER || opcode == Mcap.OP_FOOTER || opcode == Mcap.OP_DATA_END) {
                throw new McapFormatException(inner + ": a " + Mcap.recordName(opcode) + " cannot be inside a chunk");
            }
            pending.add(RecordCodec.read(opcode, b, pos + Mcap.RECORD_PREFIX_LENGTH, (int) length, inner));
            pos += Mcap.RECORD_PREFIX_LENGTH + (int) length;
        }
    }

    private McapRecord truncatedAt(long at, String what) throws McapFormatException {
        if (options.tolerateTruncation()) {
            truncated = true;
            done = true;
            return null;
        }
        throw new McapFormatException(source + ": the file ends at offset " + at + " " + what + ", before its footer: it is truncated"
                + " (a recorder killed while writing leaves such a file; mw replay plays it up to there)");
    }

    private void checkMagic(byte[] magic, String where) throws McapFormatException {
        for (int i = 0; i < magic.length; i++) {
            if (magic[i] != Mcap.MAGIC[i]) {
                if (i == 5 && where.equals("starts") && magic[0] == Mcap.MAGIC[0] && magic[4] == 'P') {
                    throw new McapFormatException(source + ": MCAP major version '" + (char) magic[5] + "' is not one this reader knows (it reads '0')");
                }
                throw new McapFormatException(source + ": " + where + " with " + hex(magic) + ", not the MCAP magic " + hex(Mcap.MAGIC)
                        + (where.equals("starts") ? ": not an MCAP file" : ": the file is damaged"));
            }
        }
    }

    private static String hex(byte[] b) {
        StringBuilder s = new StringBuilder();
        for (byte x : b) {
            s.append(String.format("%02x", x & 0xFF));
        }
        return s.toString();
    }

    /** @return false if the stream ended before {@code b} was full */
    private boolean readFully(byte[] b) throws IOException {
        int n = 0;
        while (n < b.length) {
            int r = in.read(b, n, b.length - n);
            if (r < 0) {
                return false;
            }
            n += r;
        }
        return true;
    }

    @Override
    public void close() throws IOException {
        in.close();
    }
}
