package io.robomw.platform.nxt;

import java.util.Collections;
import java.util.EnumSet;
import java.util.Locale;
import java.util.Objects;
import java.util.Set;

/**
 * One NXT output's state, as SETOUTPUTSTATE sets it and GETOUTPUTSTATE reports it: the fields the
 * firmware's output module keeps per motor ({@code c_output.iom}), with the mode bits, regulation
 * mode and run state as enums whose byte values are the firmware's (shared/protocols §1.4). The
 * telegram's layout is {@link NxtTelegram}'s.
 *
 * @param port       the output: 0 = A, 1 = B, 2 = C, or {@link NxtTelegram#ALL_OUTPUTS} (0xFF, SETOUTPUTSTATE only)
 * @param power      −100..100
 * @param mode       the mode bits set
 * @param regulation the regulation mode
 * @param turnRatio  −100..100 (synchronised motors only)
 * @param runState   the run state
 * @param tachoLimit degrees to turn before the firmware stops the motor, 0 = for ever; an unsigned 32-bit value
 */
public record OutputState(int port, int power, Set<Mode> mode, Regulation regulation, int turnRatio, RunState runState, long tachoLimit) {

    /** Mode bits ({@code c_output.iom}); the top nibble (0xF0) is the enhanced firmware's and not modelled. */
    public enum Mode {
        /** The motor is powered. */
        MOTORON(NxtTelegram.MODE_MOTORON),
        /** Brake (short the motor) when the power is 0, instead of coasting. */
        BRAKE(NxtTelegram.MODE_BRAKE),
        /** Use the regulation mode. */
        REGULATED(NxtTelegram.MODE_REGULATED);

        private final int bit;

        Mode(int bit) {
            this.bit = bit;
        }

        /** @return its bit in the mode byte */
        public int bit() {
            return bit;
        }

        /** Bits of the mode byte this model does not know; the top nibble is the enhanced firmware's. */
        private static final int UNKNOWN_BITS = 0x0F & ~(NxtTelegram.MODE_MOTORON | NxtTelegram.MODE_BRAKE | NxtTelegram.MODE_REGULATED);

        /**
         * @param bits a mode byte
         * @return the modes it sets (the top nibble, the enhanced firmware's regulation method, ignored)
         * @throws IllegalArgumentException naming the byte if it sets a bit the firmware does not have
         */
        public static Set<Mode> fromBits(int bits) {
            if ((bits & UNKNOWN_BITS) != 0) {
                throw new IllegalArgumentException(String.format(Locale.ROOT, "NXT output mode 0x%02X sets bit 0x%02X, which the firmware does not have",
                        bits, bits & UNKNOWN_BITS));
            }
            EnumSet<Mode> set = EnumSet.noneOf(Mode.class);
            for (Mode m : values()) {
                if ((bits & m.bit) != 0) {
                    set.add(m);
                }
            }
            return Collections.unmodifiableSet(set);
        }
    }

    /** Regulation modes. */
    public enum Regulation {
        /** No regulation. */
        IDLE(NxtTelegram.REGULATION_IDLE),
        /** Constant speed. */
        SPEED(NxtTelegram.REGULATION_SPEED),
        /** Two motors in step (by their block tacho counts). */
        SYNC(NxtTelegram.REGULATION_SYNC),
        /** Position regulation: enhanced and newer firmware only; this driver never sends it. */
        POSITION(0x04);

        private final int code;

        Regulation(int code) {
            this.code = code;
        }

        /** @return its byte value */
        public int code() {
            return code;
        }

        /**
         * @param code a regulation byte
         * @return its mode
         * @throws IllegalArgumentException naming the byte if the firmware has no such mode
         */
        public static Regulation fromCode(int code) {
            for (Regulation r : values()) {
                if (r.code == code) {
                    return r;
                }
            }
            throw new IllegalArgumentException(String.format(Locale.ROOT, "NXT regulation mode 0x%02X is none the firmware has (0, 1, 2, 4)", code));
        }
    }

    /** Run states. */
    public enum RunState {
        /** Idle: the output is off (a limited rotation that ended reports this). */
        IDLE(NxtTelegram.RUN_IDLE),
        /** Ramping up to the power. */
        RAMPUP(0x10),
        /** Running at the power. */
        RUNNING(NxtTelegram.RUN_RUNNING),
        /** Ramping down. */
        RAMPDOWN(0x40);

        private final int code;

        RunState(int code) {
            this.code = code;
        }

        /** @return its byte value */
        public int code() {
            return code;
        }

        /**
         * @param code a run-state byte
         * @return its run state
         * @throws IllegalArgumentException naming the byte if the firmware has no such state
         */
        public static RunState fromCode(int code) {
            for (RunState r : values()) {
                if (r.code == code) {
                    return r;
                }
            }
            throw new IllegalArgumentException(String.format(Locale.ROOT, "NXT run state 0x%02X is none the firmware has (0x00, 0x10, 0x20, 0x40)", code));
        }
    }

    /** Checks the ranges and copies the modes. */
    public OutputState {
        if ((port < 0 || port > 2) && port != NxtTelegram.ALL_OUTPUTS) {
            throw new IllegalArgumentException("NXT output port must be 0..2 (A..C) or 0xFF (all), got " + port);
        }
        if (power < -100 || power > 100) {
            throw new IllegalArgumentException("NXT output power must be -100..100, got " + power);
        }
        if (turnRatio < -100 || turnRatio > 100) {
            throw new IllegalArgumentException("NXT turn ratio must be -100..100, got " + turnRatio);
        }
        if (tachoLimit < 0 || tachoLimit > 0xFFFF_FFFFL) {
            throw new IllegalArgumentException("NXT tacho limit must fit an unsigned 32-bit field, got " + tachoLimit);
        }
        mode = mode.isEmpty() ? Set.of() : Collections.unmodifiableSet(EnumSet.copyOf(mode));
        Objects.requireNonNull(regulation, "regulation");
        Objects.requireNonNull(runState, "runState");
    }

    /** Powered, braking at power 0, regulated: how the driver runs every motor. */
    private static final Set<Mode> ON_BRAKE_REGULATED = Collections.unmodifiableSet(EnumSet.allOf(Mode.class));

    /**
     * @param port       the output
     * @param power      −100..100
     * @param regulation {@link Regulation#SPEED}, or {@link Regulation#SYNC} for a pair kept in step
     * @param tachoLimit degrees, 0 = for ever
     * @return a running motor, powered, braking, regulated, turn ratio 0
     */
    public static OutputState running(int port, int power, Regulation regulation, long tachoLimit) {
        return new OutputState(port, power, ON_BRAKE_REGULATED, regulation, 0, RunState.RUNNING, tachoLimit);
    }

    /**
     * @param port the output
     * @return the motor held at power 0: powered, braking, speed-regulated, running, no limit
     */
    public static OutputState braked(int port) {
        return new OutputState(port, 0, ON_BRAKE_REGULATED, Regulation.SPEED, 0, RunState.RUNNING, 0);
    }

    /**
     * @param port the output
     * @return the output idle, drawing no current: no mode, no regulation, run state idle
     */
    public static OutputState coasting(int port) {
        return new OutputState(port, 0, Set.of(), Regulation.IDLE, 0, RunState.IDLE, 0);
    }

    /** @return the mode byte */
    public int modeBits() {
        int bits = 0;
        for (Mode m : mode) {
            bits |= m.bit;
        }
        return bits;
    }
}
