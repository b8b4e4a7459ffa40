package io.robomw.console.mcap;

import java.nio.ByteBuffer;
import java.nio.charset.CharacterCodingException;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.util.LinkedHashMap;
import java.util.Map;

/**
 * Reads one record's content, little-endian, and refuses every field that runs past the record's
 * end, every length that does not fit, and every string that is not UTF-8, with a message naming
 * the source, the record, its offset and the field.
 */
final class LeReader {

    private final byte[] bytes;
    private final int end;
    private final String where;
    private int pos;

    /**
     * @param bytes  the bytes
     * @param offset where the content starts
     * @param length the content's length
     * @param where  "Channel record at offset 123 of FILE", for messages
     */
    LeReader(byte[] bytes, int offset, int length, String where) {
        this.bytes = bytes;
        this.pos = offset;
        this.end = offset + length;
        this.where = where;
    }

    int remaining() {
        return end - pos;
    }

    int position() {
        return pos;
    }

    private void need(int n, String field) throws McapFormatException {
        if (n < 0 || n > end - pos) {
            throw new McapFormatException(where + ": field " + field + " needs " + Integer.toUnsignedString(n) + " bytes but the record has "
                    + (end - pos) + " left");
        }
    }

    int u8(String field) throws McapFormatException {
        need(1, field);
        return bytes[pos++] & 0xFF;
    }

    int u16(String field) throws McapFormatException {
        need(2, field);
        int v = (bytes[pos] & 0xFF) | (bytes[pos + 1] & 0xFF) << 8;
        pos += 2;
        return v;
    }

    long u32(String field) throws McapFormatException {
        need(4, field);
        long v = 0;
        for (int i = 0; i < 4; i++) {
            v |= (long) (bytes[pos + i] & 0xFF) << (8 * i);
        }
        pos += 4;
        return v;
    }

    long u64(String field) throws McapFormatException {
        need(8, field);
        long v = 0;
        for (int i = 0; i < 8; i++) {
            v |= (long) (bytes[pos + i] & 0xFF) << (8 * i);
        }
        pos += 8;
        return v;
    }

    private int length32(String field) throws McapFormatException {
        long n = u32(field + " length");
        if (n > end - pos) {
            throw new McapFormatException(where + ": field " + field + " says it is " + n + " bytes long but the record has " + (end - pos) + " left");
        }
        return (int) n;
    }

    byte[] raw(int n, String field) throws McapFormatException {
        need(n, field);
        byte[] b = new byte[n];
        System.arraycopy(bytes, pos, b, 0, n);
        pos += n;
        return b;
    }

    byte[] rest() {
        byte[] b = new byte[end - pos];
        System.arraycopy(bytes, pos, b, 0, b.length);
        pos = end;
        return b;
    }

    byte[] bytes32(String field) throws McapFormatException {
        return raw(length32(field), field);
    }

    byte[] bytes64(String field) throws McapFormatException {
        long n = u64(field + " length");
        if (n < 0 || n > end - pos) {
            throw new McapFormatException(where + ": field " + field + " says it is " + Long.toUnsignedString(n) + " bytes long but the record has "
                    + (end - pos) + " left");
        }
        return raw((int) n, field);
    }

    String string(String field) throws McapFormatException {
        int n = length32(field);
        try {
            String s = StandardCharsets.UTF_8.newDecoder().onMalformedInput(CodingErrorAction.REPORT).onUnmappableCharacter(CodingErrorAction.REPORT)
                    .decode(ByteBuffer.wrap(bytes, pos, n)).toString();
            pos += n;
            return s;
        } catch (CharacterCodingException e) {
            throw new McapFormatException(where + ": field " + field + " is not UTF-8", e);
        }
    }

    Map<String, String> stringMap(String field) throws McapFormatException {
        int n = length32(field);
        LeReader in = new LeReader(bytes, pos, n, where);
        pos += n;
        Map<String, String> map = new LinkedHashMap<>();
        while (in.remaining() > 0) {
            String k = in.string(field + " key");
            String v = in.string(field + " value");
            if (map.put(k, v) != null) {
                throw new McapFormatException(where + ": field " + field + " has the key '" + k + "' twice");
            }
        }
        return map;
    }

    Map<Integer, Long> u16u64Map(String field) throws McapFormatException {
        int n = length32(field);
        if (n % 10 != 0) {
            throw new McapFormatException(where + ": field " + field + " is " + n + " bytes, not a whole number of 10-byte (u16, u64) entries");
        }
        Map<Integer, Long> map = new LinkedHashMap<>();
        for (int i = 0; i < n / 10; i++) {
            int k = u16(field + " key");
            long v = u64(field + " value");
            if (map.put(k, v) != null) {
                throw new McapFormatException(where + ": field " + field + " has the key " + k + " twice");
            }
        }
        return map;
    }
}
