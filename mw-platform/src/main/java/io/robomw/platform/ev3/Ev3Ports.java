package io.robomw.platform.ev3;

import java.util.List;

/**
 * The EV3's port names and numbers, shared by the driver and the brick emulator. Outputs A..D are
 * numbers 0..3 (for opcodes taking NO) and bits 1, 2, 4, 8 (for opcodes taking NOS); inputs
 * S1..S4 are numbers 0..3, and the motors read as sensors are 16..19.
 */
public final class Ev3Ports {

    /** The motor outputs, in port order. */
    public static final List<String> OUTPUTS = List.of("A", "B", "C", "D");
    /** Number of sensor inputs. */
    public static final int INPUTS = 4;
    /** Input number of output A read as a sensor; B..D follow. */
    public static final int FIRST_MOTOR_INPUT = 16;
    /** The layer of a single brick (no daisy chain). */
    public static final int LAYER_MASTER = 0;

    private Ev3Ports() {
    }

    /**
     * @param port an output name, A..D
     * @return its number, 0..3
     * @throws IllegalArgumentException if the EV3 has no such output
     */
    public static int outputNumber(String port) {
        int i = OUTPUTS.indexOf(port);
        if (i < 0) {
            throw new IllegalArgumentException("the EV3 has motor ports A, B, C and D, not '" + port + "'");
        }
        return i;
    }

    /**
     * @param port an output name, A..D
     * @return its bit for NOS parameters: A = 1, B = 2, C = 4, D = 8
     */
    public static int outputBit(String port) {
        return 1 << outputNumber(port);
    }

    /**
     * @param nos a NOS bit field
     * @return the outputs it names, for messages: {@code "B+C"}, or the bits in hex if beyond D
     */
    public static String outputNames(int nos) {
        if (nos <= 0 || nos > 0x0F) {
            return String.format("outputs 0x%02X", nos);
        }
        StringBuilder sb = new StringBuilder();
        for (int i = 0; i < OUTPUTS.size(); i++) {
            if ((nos & 1 << i) != 0) {
                sb.append(sb.length() == 0 ? "" : "+").append(OUTPUTS.get(i));
            }
        }
        return sb.toString();
    }

    /**
     * @param no an output number
     * @return its name, for messages
     */
    public static String outputName(int no) {
        return no >= 0 && no < OUTPUTS.size() ? OUTPUTS.get(no) : "output " + no;
    }

    /**
     * @param port an input name as a robot description gives it: {@code S1}..{@code S4}, or {@code 1}..{@code 4}
     * @return its number, 0..3
     * @throws IllegalArgumentException if the EV3 has no such input
     */
    public static int inputNumber(String port) {
        String p = port.startsWith("S") ? port.substring(1) : port;
        return switch (p) {
            case "1" -> 0;
            case "2" -> 1;
            case "3" -> 2;
            case "4" -> 3;
            default -> throw new IllegalArgumentException("the EV3 has sensor ports S1, S2, S3 and S4, not '" + port + "'");
        };
    }

    /**
     * @param no an input number
     * @return its name, for messages: {@code S1}, {@code motor A}, or the number
     */
    public static String inputName(int no) {
        if (no >= 0 && no < INPUTS) {
            return "S" + (no + 1);
        }
        if (no >= FIRST_MOTOR_INPUT && no < FIRST_MOTOR_INPUT + OUTPUTS.size()) {
            return "motor " + OUTPUTS.get(no - FIRST_MOTOR_INPUT);
        }
        return "input " + no;
    }
}
