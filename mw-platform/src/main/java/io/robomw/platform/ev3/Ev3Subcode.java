package io.robomw.platform.ev3;

import java.util.Optional;

/**
 * Sub-codes: the first parameter of the opcodes that take one ({@code bytecodes.h}).
 */
public enum Ev3Subcode {
    /** INPUT_DEVICE GET_TYPEMODE: LAYER, NO, *TYPE (DATA8), *MODE (DATA8). */
    GET_TYPEMODE(Ev3Opcode.INPUT_DEVICE, 0x05),
    /** INPUT_DEVICE READY_PCT: LAYER, NO, TYPE, MODE, VALUES, *PCT (DATA8) × VALUES. */
    READY_PCT(Ev3Opcode.INPUT_DEVICE, 0x1B),
    /** INPUT_DEVICE READY_RAW: LAYER, NO, TYPE, MODE, VALUES, *RAW (DATA32) × VALUES. */
    READY_RAW(Ev3Opcode.INPUT_DEVICE, 0x1C),
    /** INPUT_DEVICE READY_SI: LAYER, NO, TYPE (0 = keep), MODE (-1 = keep), VALUES, *SI (DATAF) × VALUES. */
    READY_SI(Ev3Opcode.INPUT_DEVICE, 0x1D),
    /** UI_READ GET_VBATT: *VOLTS (DATAF). */
    GET_VBATT(Ev3Opcode.UI_READ, 0x01),
    /** SOUND BREAK: stops the sound. */
    BREAK(Ev3Opcode.SOUND, 0x00),
    /** SOUND TONE: VOLUME (DATA8 0..100), FREQUENCY (DATA16 Hz), DURATION (DATA16 ms). */
    TONE(Ev3Opcode.SOUND, 0x01);

    private final Ev3Opcode opcode;
    private final int code;

    Ev3Subcode(Ev3Opcode opcode, int code) {
        this.opcode = opcode;
        this.code = code;
    }

    /** @return the opcode this sub-code belongs to */
    public Ev3Opcode opcode() {
        return opcode;
    }

    /** @return the sub-code's value */
    public int code() {
        return code;
    }

    /**
     * @param opcode an opcode
     * @param code   a sub-code value
     * @return the sub-code, if it is one of these
     */
    public static Optional<Ev3Subcode> of(Ev3Opcode opcode, int code) {
        for (Ev3Subcode s : values()) {
            if (s.opcode == opcode && s.code == code) {
                return Optional.of(s);
            }
        }
        return Optional.empty();
    }
}
