package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.motor.MotorState;

import java.io.ByteArrayOutputStream;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * One EV3 direct command: byte codes, the global (reply) and local variable space they use, and
 * whether a reply is wanted. {@link #encode(int)} gives the frame of {@link Ev3Frame} with a
 * message counter; the counter is chosen per request by {@link Ev3Brick}, so a command can be
 * built once and sent many times.
 *
 * <p>Built with {@link #withReply(int)} or {@link #withoutReply()}, then opcodes and parameters in
 * order. Constants go out in their shortest form ({@link Ev3Parameter#lc(int)}), as ev3-dc sends
 * them. The typed helpers ({@link Builder#outputStepSpeed} ...) add one opcode with its parameters,
 * check that results fit the reserved globals, and remember the opcode and port, so an error
 * reply names what was asked. Immutable.
 */
public final class Ev3Command {

    private final int type;
    private final int globals;
    private final int locals;
    private final byte[] code;
    private final List<String> instructions;

    private Ev3Command(int type, int globals, int locals, byte[] code, List<String> instructions) {
        this.type = type;
        this.globals = globals;
        this.locals = locals;
        this.code = code;
        this.instructions = List.copyOf(instructions);
    }

    /**
     * @param globals bytes of global variables the byte codes write and the reply carries back, 0..1021
     * @return a builder of a command whose reply is awaited (type 0x00)
     * @throws IllegalArgumentException if globals is out of range
     */
    public static Builder withReply(int globals) {
        return new Builder(Ev3Frame.DIRECT_COMMAND_REPLY, globals);
    }

    /** @return a builder of a command the brick does not answer (type 0x80, no globals) */
    public static Builder withoutReply() {
        return new Builder(Ev3Frame.DIRECT_COMMAND_NO_REPLY, 0);
    }

    /** @return the type byte: {@link Ev3Frame#DIRECT_COMMAND_REPLY} or {@link Ev3Frame#DIRECT_COMMAND_NO_REPLY} */
    public int type() {
        return type;
    }

    /** @return whether the brick answers it */
    public boolean replyWanted() {
        return type == Ev3Frame.DIRECT_COMMAND_REPLY;
    }

    /** @return bytes of global variables, which the reply carries */
    public int globals() {
        return globals;
    }

    /** @return bytes of local variables */
    public int locals() {
        return locals;
    }

    /** @return a copy of the byte codes */
    public byte[] code() {
        return code.clone();
    }

    /** @return the opcodes and ports in it, for messages, e.g. {@code opOUTPUT_GET_COUNT on output A} */
    public List<String> instructions() {
        return instructions;
    }

    /** @return the instructions joined, for messages */
    public String describe() {
        return String.join(", ", instructions);
    }

    /**
     * @param counter the message counter, 0..65535 (the brick echoes it in the reply)
     * @return the whole frame, from its length field
     */
    public byte[] encode(int counter) {
        if (counter < 0 || counter > 0xFFFF) {
            throw new IllegalArgumentException("the message counter is an unsigned 16-bit field, counter=" + counter);
        }
        byte[] frame = new byte[Ev3Frame.COMMAND_HEADER_LENGTH + code.length];
        LittleEndian.putU16(frame, Ev3Frame.LENGTH_FIELD_OFFSET, frame.length - Ev3Frame.LENGTH_FIELD_SIZE);
        LittleEndian.putU16(frame, Ev3Frame.COUNTER_FIELD_OFFSET, counter);
        frame[Ev3Frame.TYPE_FIELD_OFFSET] = (byte) type;
        LittleEndian.putU16(frame, Ev3Frame.VARS_FIELD_OFFSET, Ev3Frame.vars(locals, globals));
        System.arraycopy(code, 0, frame, Ev3Frame.CODE_OFFSET, code.length);
        return frame;
    }

    @Override
    public String toString() {
        return "Ev3Command[" + Ev3Frame.typeName(type) + ", globals=" + globals + ", locals=" + locals + ", " + describe() + "]";
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof Ev3Command c && c.type == type && c.globals == globals && c.locals == locals && Arrays.equals(c.code, code);
    }

    @Override
    public int hashCode() {
        return Arrays.hashCode(code) * 31 + type * 7 + globals + locals * 1024;
    }

    /** Builds a command; not thread-safe. */
    public static final class Builder {

        private final int type;
        private final int globals;
        private int locals;
        private final ByteArrayOutputStream code = new ByteArrayOutputStream();
        private final List<String> instructions = new ArrayList<>();

        private Builder(int type, int globals) {
            Ev3Frame.vars(0, globals);
            this.type = type;
            this.globals = globals;
        }

        /**
         * @param bytes local-variable bytes, 0..63
         * @return this
         */
        public Builder locals(int bytes) {
            Ev3Frame.vars(bytes, globals);
            this.locals = bytes;
            return this;
        }

        /**
         * Starts an instruction; its parameters follow.
         *
         * @param opcode the opcode
         * @return this
         */
        public Builder op(Ev3Opcode opcode) {
            return op(opcode, "op" + opcode.name());
        }

        private Builder op(Ev3Opcode opcode, String description) {
            code.write(opcode.code());
            instructions.add(description);
            return this;
        }

        /**
         * Adds a sub-code, as a constant parameter.
         *
         * @param subcode the sub-code
         * @return this
         */
        public Builder sub(Ev3Subcode subcode) {
            return lc(subcode.code());
        }

        /**
         * @param v a constant
         * @return this, with the constant in its shortest form
         */
        public Builder lc(int v) {
            return raw(Ev3Parameter.lc(v));
        }

        /**
         * @param v -32..31
         * @return this, with LC0(v)
         */
        public Builder lc0(int v) {
            return raw(Ev3Parameter.lc0(v));
        }

        /**
         * @param v -128..127
         * @return this, with LC1(v)
         */
        public Builder lc1(int v) {
            return raw(Ev3Parameter.lc1(v));
        }

        /**
         * @param v -32768..32767
         * @return this, with LC2(v)
         */
        public Builder lc2(int v) {
            return raw(Ev3Parameter.lc2(v));
        }

        /**
         * @param v any int
         * @return this, with LC4(v)
         */
        public Builder lc4(int v) {
            return raw(Ev3Parameter.lc4(v));
        }

        /**
         * @param text ASCII text
         * @return this, with LCS(text)
         */
        public Builder lcs(String text) {
            return raw(Ev3Parameter.lcs(text));
        }

        /**
         * @param offset a global-variable byte offset
         * @return this, with a reference to it in its shortest form
         */
        public Builder gv(int offset) {
            return raw(Ev3Parameter.gv(offset));
        }

        /**
         * @param offset a local-variable byte offset
         * @return this, with a reference to it in its shortest form
         */
        public Builder lv(int offset) {
            return raw(Ev3Parameter.lv(offset));
        }

        /**
         * @param encoded an encoded parameter
         * @return this
         */
        public Builder raw(byte[] encoded) {
            code.writeBytes(encoded);
            return this;
        }

        // ---- typed instructions (layer 0) ----

        /**
         * opOUTPUT_STOP.
         *
         * @param nos  outputs, as a bit field
         * @param mode brake (1) or coast (0)
         * @return this
         */
        public Builder outputStop(int nos, MotorState.StopMode mode) {
            return op(Ev3Opcode.OUTPUT_STOP, "opOUTPUT_STOP on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos).lc(mode == MotorState.StopMode.BRAKE ? 1 : 0);
        }

        /**
         * opOUTPUT_POWER: sets the unregulated power; {@link #outputStart} runs it.
         *
         * @param nos   outputs
         * @param power -100..100
         * @return this
         */
        public Builder outputPower(int nos, int power) {
            requirePercent("power", power);
            return op(Ev3Opcode.OUTPUT_POWER, "opOUTPUT_POWER on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos).lc(power);
        }

        /**
         * opOUTPUT_SPEED: sets the regulated speed; {@link #outputStart} runs it.
         *
         * @param nos   outputs
         * @param speed -100..100
         * @return this
         */
        public Builder outputSpeed(int nos, int speed) {
            requirePercent("speed", speed);
            return op(Ev3Opcode.OUTPUT_SPEED, "opOUTPUT_SPEED on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos).lc(speed);
        }

        /**
         * opOUTPUT_START.
         *
         * @param nos outputs
         * @return this
         */
        public Builder outputStart(int nos) {
            return op(Ev3Opcode.OUTPUT_START, "opOUTPUT_START on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos);
        }

        /**
         * opOUTPUT_STEP_SPEED: runs at a regulated speed for step1 + step2 + step3 degrees (ramping
         * up over step1 and down over step3), then stops.
         *
         * @param nos   outputs
         * @param speed -100..100; its sign gives the direction
         * @param step1 ramp-up, degrees
         * @param step2 constant speed, degrees
         * @param step3 ramp-down, degrees
         * @param end   how to stop at the end
         * @return this
         */
        public Builder outputStepSpeed(int nos, int speed, int step1, int step2, int step3, MotorState.StopMode end) {
            requirePercent("speed", speed);
            if (step1 < 0 || step2 < 0 || step3 < 0) {
                throw new IllegalArgumentException("steps are degrees, 0 or more; got " + step1 + ", " + step2 + ", " + step3);
            }
            return op(Ev3Opcode.OUTPUT_STEP_SPEED, "opOUTPUT_STEP_SPEED on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos).lc(speed).lc(step1).lc(step2).lc(step3)
                    .lc(end == MotorState.StopMode.BRAKE ? 1 : 0);
        }

        /**
         * opOUTPUT_READY: the command is held until the outputs' step commands are done.
         *
         * @param nos outputs
         * @return this
         */
        public Builder outputReady(int nos) {
            return op(Ev3Opcode.OUTPUT_READY, "opOUTPUT_READY on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos);
        }

        /**
         * opOUTPUT_CLR_COUNT: zeroes the tacho counts.
         *
         * @param nos outputs
         * @return this
         */
        public Builder outputClrCount(int nos) {
            return op(Ev3Opcode.OUTPUT_CLR_COUNT, "opOUTPUT_CLR_COUNT on output " + Ev3Ports.outputNames(nos))
                    .lc(Ev3Ports.LAYER_MASTER).lc(nos);
        }

        /**
         * opOUTPUT_GET_COUNT: the tacho count as DATA32 degrees.
         *
         * @param no           the output number, 0..3
         * @param globalOffset where the 4 result bytes go
         * @return this
         */
        public Builder outputGetCount(int no, int globalOffset) {
            requireGlobals("opOUTPUT_GET_COUNT", globalOffset, 4);
            return op(Ev3Opcode.OUTPUT_GET_COUNT, "opOUTPUT_GET_COUNT on output " + Ev3Ports.outputName(no))
                    .lc(Ev3Ports.LAYER_MASTER).lc(no).gv(globalOffset);
        }

        /**
         * opINPUT_DEVICE READY_SI: one value in SI units as DATAF, once the device is ready.
         *
         * @param no           the input number, 0..3 (16..19 for motors)
         * @param deviceType   the device type to expect (0 keeps the current one)
         * @param mode         the mode (-1 keeps the current one)
         * @param globalOffset where the 4 result bytes go
         * @return this
         */
        public Builder inputReadySi(int no, int deviceType, int mode, int globalOffset) {
            return inputReady(Ev3Subcode.READY_SI, no, deviceType, mode, globalOffset, 4);
        }

        /**
         * opINPUT_DEVICE READY_RAW: one raw value as DATA32, once the device is ready.
         *
         * @param no           the input number
         * @param deviceType   the device type (0 keeps)
         * @param mode         the mode (-1 keeps)
         * @param globalOffset where the 4 result bytes go
         * @return this
         */
        public Builder inputReadyRaw(int no, int deviceType, int mode, int globalOffset) {
            return inputReady(Ev3Subcode.READY_RAW, no, deviceType, mode, globalOffset, 4);
        }

        /**
         * opINPUT_DEVICE READY_PCT: one value in percent as DATA8, once the device is ready.
         *
         * @param no           the input number
         * @param deviceType   the device type (0 keeps)
         * @param mode         the mode (-1 keeps)
         * @param globalOffset where the result byte goes
         * @return this
         */
        public Builder inputReadyPct(int no, int deviceType, int mode, int globalOffset) {
            return inputReady(Ev3Subcode.READY_PCT, no, deviceType, mode, globalOffset, 1);
        }

        private Builder inputReady(Ev3Subcode subcode, int no, int deviceType, int mode, int globalOffset, int width) {
            requireGlobals("opINPUT_DEVICE " + subcode, globalOffset, width);
            return op(Ev3Opcode.INPUT_DEVICE, "opINPUT_DEVICE " + subcode + " on input " + Ev3Ports.inputName(no))
                    .sub(subcode).lc(Ev3Ports.LAYER_MASTER).lc(no).lc(deviceType).lc(mode).lc(1).gv(globalOffset);
        }

        /**
         * opINPUT_READ: one value in percent as DATA8.
         *
         * @param no           the input number
         * @param deviceType   the device type (0 keeps)
         * @param mode         the mode (-1 keeps)
         * @param globalOffset where the result byte goes
         * @return this
         */
        public Builder inputRead(int no, int deviceType, int mode, int globalOffset) {
            requireGlobals("opINPUT_READ", globalOffset, 1);
            return op(Ev3Opcode.INPUT_READ, "opINPUT_READ on input " + Ev3Ports.inputName(no))
                    .lc(Ev3Ports.LAYER_MASTER).lc(no).lc(deviceType).lc(mode).gv(globalOffset);
        }

        /**
         * opUI_READ GET_VBATT: the battery voltage as DATAF volts.
         *
         * @param globalOffset where the 4 result bytes go
         * @return this
         */
        public Builder uiReadVbatt(int globalOffset) {
            requireGlobals("opUI_READ GET_VBATT", globalOffset, 4);
            return op(Ev3Opcode.UI_READ, "opUI_READ GET_VBATT").sub(Ev3Subcode.GET_VBATT).gv(globalOffset);
        }

        /**
         * opSOUND TONE.
         *
         * @param volume  0..100
         * @param hertz   frequency
         * @param millis  duration
         * @return this
         */
        public Builder soundTone(int volume, int hertz, int millis) {
            if (volume < 0 || volume > 100) {
                throw new IllegalArgumentException("volume must be 0..100, volume=" + volume);
            }
            if (hertz < 0 || hertz > 0xFFFF || millis < 0 || millis > 0xFFFF) {
                throw new IllegalArgumentException("frequency and duration are unsigned 16-bit values, hertz=" + hertz + ", millis=" + millis);
            }
            return op(Ev3Opcode.SOUND, "opSOUND TONE").sub(Ev3Subcode.TONE).lc(volume).lc((short) hertz).lc((short) millis);
        }

        private void requireGlobals(String what, int offset, int width) {
            if (offset < 0 || offset + width > globals) {
                throw new IllegalArgumentException(what + " writes " + width + " byte(s) at global offset " + offset
                        + ", but the command reserves " + globals + " global byte(s); reserve more with withReply(globals)");
            }
        }

        private static void requirePercent(String what, int value) {
            if (value < -100 || value > 100) {
                throw new IllegalArgumentException(what + " must be -100..100 percent, " + what + "=" + value);
            }
        }

        /**
         * @return the command
         * @throws IllegalArgumentException if it has no byte codes, or its frame would exceed the
         *                                  firmware's {@value Ev3Frame#MAX_COMMAND_LENGTH}-byte length field
         */
        public Ev3Command build() {
            byte[] bytes = code.toByteArray();
            if (bytes.length == 0) {
                throw new IllegalArgumentException("a direct command needs at least one byte code; the firmware refuses an empty one");
            }
            int length = Ev3Frame.COMMAND_HEADER_LENGTH - Ev3Frame.LENGTH_FIELD_SIZE + bytes.length;
            if (length > Ev3Frame.MAX_COMMAND_LENGTH) {
                throw new IllegalArgumentException("encoded message exceeds the EV3's maximum of " + Ev3Frame.MAX_COMMAND_LENGTH
                        + " bytes after the length field, length=" + length);
            }
            return new Ev3Command(type, globals, locals, bytes, instructions);
        }
    }
}
