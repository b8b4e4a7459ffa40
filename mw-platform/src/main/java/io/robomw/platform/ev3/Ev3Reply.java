package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import java.util.Arrays;
import java.util.Objects;

/**
 * A reply to a direct command (see {@link Ev3Frame}): the echoed message counter, whether the
 * command ran ({@link Ev3Frame#DIRECT_REPLY}) or failed ({@link Ev3Frame#DIRECT_REPLY_ERROR}),
 * and the global variables, from which the typed getters read results little-endian. The brick
 * emulator encodes replies with {@link #encode()}; the driver decodes them with
 * {@link #decode(byte[])}.
 *
 * <p>Result markers: the firmware reports "no value" as DATA8 -128, DATA16 -32768, DATA32
 * 0x80000000 and DATAF NaN ({@link #NAN_DATA8} ...).
 *
 * @param counter the message counter, echoed from the command
 * @param type    {@link Ev3Frame#DIRECT_REPLY} or {@link Ev3Frame#DIRECT_REPLY_ERROR}
 * @param globals the global variables (none after a malformed header)
 */
public record Ev3Reply(int counter, int type, byte[] globals) {

    /** DATA8's "no value". */
    public static final int NAN_DATA8 = Byte.MIN_VALUE;
    /** DATA16's "no value". */
    public static final int NAN_DATA16 = Short.MIN_VALUE;
    /** DATA32's "no value". */
    public static final int NAN_DATA32 = Integer.MIN_VALUE;

    /** Checks the fields and copies the globals. */
    public Ev3Reply {
        if (counter < 0 || counter > 0xFFFF) {
            throw new IllegalArgumentException("the message counter is an unsigned 16-bit field, counter=" + counter);
        }
        if (type != Ev3Frame.DIRECT_REPLY && type != Ev3Frame.DIRECT_REPLY_ERROR) {
            throw new IllegalArgumentException(String.format("a direct reply's type is 0x02 or 0x04, type=0x%02X", type));
        }
        Objects.requireNonNull(globals, "globals");
        if (globals.length > Ev3Frame.MAX_GLOBALS) {
            throw new IllegalArgumentException("a reply carries at most " + Ev3Frame.MAX_GLOBALS + " global bytes, got " + globals.length);
        }
        globals = globals.clone();
    }

    /**
     * @param counter the command's counter
     * @param globals its global variables after running
     * @return a {@link Ev3Frame#DIRECT_REPLY}
     */
    public static Ev3Reply ok(int counter, byte[] globals) {
        return new Ev3Reply(counter, Ev3Frame.DIRECT_REPLY, globals);
    }

    /**
     * @param counter the command's counter
     * @param globals its global variables as far as it ran; empty after a malformed header
     * @return a {@link Ev3Frame#DIRECT_REPLY_ERROR}
     */
    public static Ev3Reply error(int counter, byte[] globals) {
        return new Ev3Reply(counter, Ev3Frame.DIRECT_REPLY_ERROR, globals);
    }

    /**
     * Decodes a whole reply frame.
     *
     * @param frame the frame, from its length field
     * @return the reply
     * @throws IllegalArgumentException if the frame is shorter than its length field says (a
     *                                  partial frame), longer, shorter than a reply header, or of
     *                                  another type; the message gives the numbers
     */
    public static Ev3Reply decode(byte[] frame) {
        if (frame.length < Ev3Frame.REPLY_HEADER_LENGTH) {
            throw new IllegalArgumentException("an EV3 reply has at least " + Ev3Frame.REPLY_HEADER_LENGTH + " bytes (length, counter, type), got "
                    + frame.length);
        }
        int length = Ev3Frame.length(frame);
        if (length != frame.length - Ev3Frame.LENGTH_FIELD_SIZE) {
            throw new IllegalArgumentException("the reply's length field announces " + length + " bytes after it, but "
                    + (frame.length - Ev3Frame.LENGTH_FIELD_SIZE) + " are there");
        }
        return new Ev3Reply(Ev3Frame.counter(frame), Ev3Frame.type(frame),
                Arrays.copyOfRange(frame, Ev3Frame.GLOBALS_OFFSET, frame.length));
    }

    /** @return the whole frame, from its length field */
    public byte[] encode() {
        byte[] frame = new byte[Ev3Frame.REPLY_HEADER_LENGTH + globals.length];
        LittleEndian.putU16(frame, Ev3Frame.LENGTH_FIELD_OFFSET, frame.length - Ev3Frame.LENGTH_FIELD_SIZE);
        LittleEndian.putU16(frame, Ev3Frame.COUNTER_FIELD_OFFSET, counter);
        frame[Ev3Frame.TYPE_FIELD_OFFSET] = (byte) type;
        System.arraycopy(globals, 0, frame, Ev3Frame.GLOBALS_OFFSET, globals.length);
        return frame;
    }

    /** @return whether the command ran */
    public boolean isOk() {
        return type == Ev3Frame.DIRECT_REPLY;
    }

    /** @return a copy of the global variables */
    @Override
    public byte[] globals() {
        return globals.clone();
    }

    /**
     * @param offset a global offset
     * @return the DATA8 there, signed
     */
    public int data8(int offset) {
        require(offset, 1);
        return globals[offset];
    }

    /**
     * @param offset a global offset
     * @return the DATA16 there, signed, little-endian
     */
    public int data16(int offset) {
        require(offset, 2);
        return LittleEndian.s16(globals, offset);
    }

    /**
     * @param offset a global offset
     * @return the DATA32 there, signed, little-endian
     */
    public int data32(int offset) {
        require(offset, 4);
        return LittleEndian.s32(globals, offset);
    }

    /**
     * @param offset a global offset
     * @return the DATAF there: IEEE-754 single precision, little-endian
     */
    public float dataF(int offset) {
        require(offset, 4);
        return LittleEndian.f32(globals, offset);
    }

    private void require(int offset, int width) {
        if (offset < 0 || offset + width > globals.length) {
            throw new IndexOutOfBoundsException("reading " + width + " byte(s) at global offset " + offset + " of a reply carrying "
                    + globals.length + " global byte(s)");
        }
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof Ev3Reply r && r.counter == counter && r.type == type && Arrays.equals(r.globals, globals);
    }

    @Override
    public int hashCode() {
        return Arrays.hashCode(globals) * 31 + counter * 7 + type;
    }

    @Override
    public String toString() {
        return "Ev3Reply[" + Ev3Frame.typeName(type) + ", counter=" + counter + ", globals=" + globals.length + " byte(s)]";
    }
}
