package io.robomw.sim.emulator.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.ev3.Ev3CodeReader;
import io.robomw.platform.ev3.Ev3Frame;
import io.robomw.platform.ev3.Ev3Parameter;

/**
 * The variable space of one direct command while the emulator runs it: its byte codes, its global
 * variables (which the reply carries) and its local variables. Input parameters are read as the
 * opcode's data type wants them (a constant is truncated to it; a variable is read from its space,
 * little-endian); result parameters must be variables and are written into their space. Anything
 * the firmware's virtual machine would fail on (byte codes ending inside a parameter, a result
 * given as a constant, an offset outside the space) throws {@link Failure}.
 *
 * <p>Not thread-safe: one per command, used under the emulator's firmware lock.
 */
final class Ev3Vm {

    /** The virtual machine failed: the command gets {@code DIRECT_REPLY_ERROR}. */
    static final class Failure extends RuntimeException {
        private static final long serialVersionUID = 1L;

        Failure(String message) {
            super(message, null, false, false);
        }
    }

    private final Ev3CodeReader code;
    private final byte[] globals;
    private final byte[] locals;

    /**
     * @param code    the byte codes
     * @param globals global-variable bytes
     * @param locals  local-variable bytes
     */
    Ev3Vm(Ev3CodeReader code, int globals, int locals) {
        this.code = code;
        this.globals = new byte[globals];
        this.locals = new byte[locals];
    }

    /** @return the global variables as they are now */
    byte[] globals() {
        return globals.clone();
    }

    /** @return whether byte codes are left */
    boolean hasMore() {
        return code.hasMore();
    }

    /** @return offset of the next byte code, for messages */
    int position() {
        return code.position();
    }

    /** @return the next opcode byte */
    int opcode() {
        try {
            return code.nextByte();
        } catch (IllegalArgumentException e) {
            throw new Failure(e.getMessage());
        }
    }

    private Ev3Parameter parameter() {
        try {
            return code.nextParameter();
        } catch (IllegalArgumentException e) {
            throw new Failure(e.getMessage());
        }
    }

    /** @return the next parameter as DATA8 */
    int data8() {
        Ev3Parameter p = parameter();
        return p.isVariable() ? space(p, 1)[p.value()] : (byte) constant(p);
    }

    /** @return the next parameter as DATA16 */
    int data16() {
        Ev3Parameter p = parameter();
        return p.isVariable() ? LittleEndian.s16(space(p, 2), p.value()) : (short) constant(p);
    }

    /** @return the next parameter as DATA32 */
    int data32() {
        Ev3Parameter p = parameter();
        return p.isVariable() ? LittleEndian.s32(space(p, 4), p.value()) : constant(p);
    }

    /**
     * @param value a DATA8 result
     */
    void store8(int value) {
        Ev3Parameter p = result();
        space(p, 1)[p.value()] = (byte) value;
    }

    /**
     * @param value a DATA32 result
     */
    void store32(int value) {
        Ev3Parameter p = result();
        LittleEndian.putU32(space(p, 4), p.value(), value);
    }

    /**
     * @param value a DATAF result
     */
    void storeF(float value) {
        Ev3Parameter p = result();
        LittleEndian.putF32(space(p, 4), p.value(), value);
    }

    private Ev3Parameter result() {
        int at = code.position();
        Ev3Parameter p = parameter();
        if (!p.isVariable()) {
            throw new Failure("the result parameter at byte " + at + " is " + p + ", not a variable");
        }
        return p;
    }

    private static int constant(Ev3Parameter p) {
        if (p.kind() != Ev3Parameter.Kind.CONSTANT) {
            throw new Failure("a number was expected, got " + p);
        }
        return p.value();
    }

    private byte[] space(Ev3Parameter p, int width) {
        byte[] space = p.kind() == Ev3Parameter.Kind.GLOBAL ? globals : locals;
        if (p.value() < 0 || p.value() + width > space.length) {
            throw new Failure(p + " with " + width + " byte(s) lies outside the " + space.length + " "
                    + (p.kind() == Ev3Parameter.Kind.GLOBAL ? "global" : "local") + " byte(s) the command reserved");
        }
        return space;
    }
}
