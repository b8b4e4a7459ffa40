package io.robomw.platform.mavlink.wire;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;
import java.util.Objects;

/**
 * A message's fields: its payload at full length (a cut payload zero-extended), read and written
 * field by field through the {@link Field}s of its {@link MessageType}. Integer fields read as
 * {@code long} (unsigned ones widened: a {@code uint32_t} 0xFFFFFFFF reads as 4294967295; a
 * {@code uint64_t} as the same 64 bits), floating-point ones as {@code double}; text
 * ({@code char[N]}) as a string up to its first NUL.
 *
 * <p>Not thread-safe: one thread fills it, and a payload handed on is not changed afterwards.
 */
public final class Payload {

    private final MessageType type;
    private final byte[] bytes;

    private Payload(MessageType type, byte[] bytes) {
        this.type = type;
        this.bytes = bytes;
    }

    /**
     * @param type a message type
     * @return a payload of that type with every field zero
     */
    public static Payload of(MessageType type) {
        return new Payload(type, new byte[type.maxLength()]);
    }

    /**
     * Reads a payload as it came on the wire: shorter ones are zero-extended; bytes beyond the
     * fields this definition knows (a newer sender's extensions) are ignored.
     *
     * @param type   the message type
     * @param wire   the payload bytes
     * @param offset where they start
     * @param length how many there are
     * @return the payload
     */
    public static Payload fromWire(MessageType type, byte[] wire, int offset, int length) {
        byte[] full = new byte[type.maxLength()];
        System.arraycopy(wire, offset, full, 0, Math.min(length, full.length));
        return new Payload(type, full);
    }

    /** @return its message type */
    public MessageType type() {
        return type;
    }

    /**
     * @return the payload as a MAVLink 2 frame carries it: trailing zero bytes cut, but never the
     *         first byte (an all-zero payload is one byte long)
     */
    public byte[] toWire() {
        int n = bytes.length;
        while (n > 1 && bytes[n - 1] == 0) {
            n--;
        }
        return Arrays.copyOf(bytes, n);
    }

    /** @return every byte at full length (a copy) */
    public byte[] bytes() {
        return bytes.clone();
    }

    private Field own(Field f) {
        if (Objects.requireNonNull(f, "field").message() != type) {
            throw new IllegalArgumentException("field " + f + " is not a field of " + type.name());
        }
        return f;
    }

    private int at(Field f, int index) {
        own(f);
        int count = Math.max(1, f.arrayLength());
        if (index < 0 || index >= count) {
            throw new IndexOutOfBoundsException("field " + f + " has " + count + " element(s); index " + index + " is outside");
        }
        return f.offset() + index * f.type().size();
    }

    /**
     * @param f an integer field (or one element of a character array)
     * @return its value
     */
    public long getLong(Field f) {
        return getLong(f, 0);
    }

    /**
     * @param f     an integer array field
     * @param index the element
     * @return its value
     */
    public long getLong(Field f, int index) {
        int o = at(f, index);
        return switch (f.type()) {
            case UINT8_T, CHAR -> bytes[o] & 0xFFL;
            case INT8_T -> bytes[o];
            case UINT16_T -> raw(o, 2);
            case INT16_T -> (short) raw(o, 2);
            case UINT32_T -> raw(o, 4);
            case INT32_T -> (int) raw(o, 4);
            case UINT64_T, INT64_T -> raw(o, 8);
            case FLOAT, DOUBLE -> throw new IllegalArgumentException("field " + f + " is " + f.type().typeName() + "; read it with getDouble");
        };
    }

    /**
     * @param f any numeric field
     * @return its value (an integer field's as a double)
     */
    public double getDouble(Field f) {
        return getDouble(f, 0);
    }

    /**
     * @param f     a numeric array field
     * @param index the element
     * @return its value
     */
    public double getDouble(Field f, int index) {
        int o = at(f, index);
        return switch (f.type()) {
            case FLOAT -> Float.intBitsToFloat((int) raw(o, 4));
            case DOUBLE -> Double.longBitsToDouble(raw(o, 8));
            case UINT64_T -> unsigned64(raw(o, 8));
            default -> getLong(f, index);
        };
    }

    /**
     * @param f a field
     * @return its value as a float ({@code float} fields exactly)
     */
    public float getFloat(Field f) {
        return (float) getDouble(f, 0);
    }

    /**
     * @param f a {@code char[N]} field
     * @return its text up to the first NUL (as bytes 1:1 to characters 0-255, as MAVLink text is ASCII)
     */
    public String getText(Field f) {
        own(f);
        if (f.type() != FieldType.CHAR) {
            throw new IllegalArgumentException("field " + f + " is " + f.type().typeName() + ", not text");
        }
        int n = 0;
        int max = Math.max(1, f.arrayLength());
        while (n < max && bytes[f.offset() + n] != 0) {
            n++;
        }
        return new String(bytes, f.offset(), n, StandardCharsets.ISO_8859_1);
    }

    /**
     * Sets an integer field (the value's low bits, as a C cast does).
     *
     * @param f     the field
     * @param value the value
     * @return this
     */
    public Payload set(Field f, long value) {
        return set(f, 0, value);
    }

    /**
     * Sets one element of an integer array field.
     *
     * @param f     the field
     * @param index the element
     * @param value the value
     * @return this
     */
    public Payload set(Field f, int index, long value) {
        int o = at(f, index);
        switch (f.type()) {
            case FLOAT -> put(o, 4, Float.floatToRawIntBits(value));
            case DOUBLE -> put(o, 8, Double.doubleToRawLongBits(value));
            default -> put(o, f.type().size(), value);
        }
        return this;
    }

    /**
     * Sets a numeric field; an integer field takes the value rounded towards zero.
     *
     * @param f     the field
     * @param value the value
     * @return this
     */
    public Payload set(Field f, double value) {
        return set(f, 0, value);
    }

    /**
     * Sets one element of a numeric array field.
     *
     * @param f     the field
     * @param index the element
     * @param value the value
     * @return this
     */
    public Payload set(Field f, int index, double value) {
        int o = at(f, index);
        switch (f.type()) {
            case FLOAT -> put(o, 4, Float.floatToRawIntBits((float) value));
            case DOUBLE -> put(o, 8, Double.doubleToRawLongBits(value));
            default -> put(o, f.type().size(), (long) value);
        }
        return this;
    }

    /**
     * Sets a text field: its characters as bytes (0-255), cut to the field's length, NUL-padded.
     *
     * @param f    a {@code char[N]} field
     * @param text the text
     * @return this
     */
    public Payload setText(Field f, String text) {
        own(f);
        if (f.type() != FieldType.CHAR) {
            throw new IllegalArgumentException("field " + f + " is " + f.type().typeName() + ", not text");
        }
        int max = Math.max(1, f.arrayLength());
        Arrays.fill(bytes, f.offset(), f.offset() + max, (byte) 0);
        for (int i = 0; i < Math.min(max, text.length()); i++) {
            char c = text.charAt(i);
            bytes[f.offset() + i] = (byte) (c <= 0xFF ? c : '?');
        }
        return this;
    }

    /**
     * Sets the bytes of a {@code uint8_t} array field (a key), cut or zero-padded to its length.
     *
     * @param f     the field
     * @param value the bytes
     * @return this
     */
    public Payload setBytes(Field f, byte[] value) {
        own(f);
        if (f.type() != FieldType.UINT8_T && f.type() != FieldType.CHAR) {
            throw new IllegalArgumentException("field " + f + " is " + f.type().typeName() + ", not bytes");
        }
        int max = Math.max(1, f.arrayLength());
        Arrays.fill(bytes, f.offset(), f.offset() + max, (byte) 0);
        System.arraycopy(value, 0, bytes, f.offset(), Math.min(max, value.length));
        return this;
    }

    /**
     * @param f a {@code uint8_t} or {@code char} array field
     * @return its bytes
     */
    public byte[] getBytes(Field f) {
        own(f);
        return Arrays.copyOfRange(bytes, f.offset(), f.offset() + f.size());
    }

    private long raw(int o, int size) {
        long v = 0;
        for (int i = size - 1; i >= 0; i--) {
            v = v << 8 | (bytes[o + i] & 0xFFL);
        }
        return v;
    }

    private void put(int o, int size, long v) {
        for (int i = 0; i < size; i++) {
            bytes[o + i] = (byte) (v >>> (8 * i));
        }
    }

    private static double unsigned64(long v) {
        return v >= 0 ? v : (double) (v >>> 1) * 2 + (v & 1);
    }

    @Override
    public String toString() {
        StringBuilder s = new StringBuilder(type.name()).append('{');
        boolean first = true;
        for (Field f : type.fields()) {
            if (!first) {
                s.append(", ");
            }
            first = false;
            s.append(f.name()).append('=');
            if (f.type() == FieldType.CHAR && f.arrayLength() > 0) {
                s.append('"').append(getText(f)).append('"');
            } else if (f.arrayLength() > 0) {
                s.append('[').append(f.arrayLength()).append(']');
            } else if (f.type().integer()) {
                s.append(getLong(f));
            } else {
                s.append(getDouble(f));
            }
        }
        return s.append('}').toString();
    }
}
