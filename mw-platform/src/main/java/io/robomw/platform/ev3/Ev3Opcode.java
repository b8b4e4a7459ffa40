package io.robomw.platform.ev3;

import java.util.Optional;

/**
 * The EV3 byte-code opcodes the driver sends and the emulator runs, with their parameters as
 * {@code lms2012/lms2012/source/bytecodes.c} gives them. {@code *} marks a result: a reference to
 * a global or local variable that the brick writes. LAYER is 0 for a single brick; NOS is a bit
 * field of outputs (A = 1, B = 2, C = 4, D = 8); NO is one port number (outputs 0..3, inputs
 * 0..3, and 16..19 for the motors read as sensors).
 */
public enum Ev3Opcode {
    /** No operation. */
    NOP(0x01),
    /** UI_READ sub-code, then its parameters; GET_VBATT: *VOLTS (DATAF). */
    UI_READ(0x81),
    /** SOUND sub-code, then its parameters; TONE: VOLUME (DATA8), FREQUENCY (DATA16 Hz), DURATION (DATA16 ms). */
    SOUND(0x94),
    /** INPUT_DEVICE sub-code, then its parameters; READY_SI: LAYER, NO, TYPE, MODE, VALUES, *VALUE (DATAF) × VALUES. */
    INPUT_DEVICE(0x99),
    /** LAYER, NO, TYPE, MODE, *PCT (DATA8). */
    INPUT_READ(0x9A),
    /** LAYER, NO, TYPE, MODE, *SI (DATAF). */
    INPUT_READSI(0x9D),
    /** LAYER, NOS, BRAKE (0 coast, 1 brake). */
    OUTPUT_STOP(0xA3),
    /** LAYER, NOS, POWER (DATA8, -100..100, unregulated); needs {@link #OUTPUT_START}. */
    OUTPUT_POWER(0xA4),
    /** LAYER, NOS, SPEED (DATA8, -100..100, regulated); needs {@link #OUTPUT_START}. */
    OUTPUT_SPEED(0xA5),
    /** LAYER, NOS. */
    OUTPUT_START(0xA6),
    /** LAYER, NO, *SPEED (DATA8), *TACHO (DATA32). */
    OUTPUT_READ(0xA8),
    /** LAYER, NOS, *BUSY (DATA8). */
    OUTPUT_TEST(0xA9),
    /** LAYER, NOS; holds the command until the outputs' step or time commands are done. */
    OUTPUT_READY(0xAA),
    /** LAYER, NOS, SPEED (DATA8), STEP1 ramp-up, STEP2 constant, STEP3 ramp-down (DATA32 degrees), BRAKE; starts the motors. */
    OUTPUT_STEP_SPEED(0xAE),
    /** LAYER, NOS: zeroes the tacho counts. */
    OUTPUT_CLR_COUNT(0xB2),
    /** LAYER, NO (a port number, not a bit field), *TACHO (DATA32 degrees). */
    OUTPUT_GET_COUNT(0xB3);

    private final int code;

    Ev3Opcode(int code) {
        this.code = code;
    }

    /** @return the opcode byte */
    public int code() {
        return code;
    }

    /**
     * @param code an opcode byte
     * @return the opcode, if it is one of these
     */
    public static Optional<Ev3Opcode> of(int code) {
        for (Ev3Opcode op : values()) {
            if (op.code == code) {
                return Optional.of(op);
            }
        }
        return Optional.empty();
    }

    /**
     * @param code an opcode byte
     * @return its name, for messages: {@code opOUTPUT_STOP} or {@code opcode 0xFE}
     */
    public static String describe(int code) {
        return of(code).map(op -> "op" + op.name()).orElse(String.format("opcode 0x%02X", code));
    }
}
