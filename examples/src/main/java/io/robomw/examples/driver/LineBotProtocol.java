package io.robomw.examples.driver;

import java.util.Locale;

/**
 * The LineBot's serial protocol, version 1: a made-up hobby robot board (in the style of the
 * Arduino-based boards that speak text over USB serial) with two motors, A and B, each with an
 * encoder that counts degrees, and two inputs, 1 and 2, for a ranger (centimetres) or a switch.
 *
 * <pre>
 * line:     ASCII, fields separated by one space, ending in LF (0x0A); at most {@value #MAX_LINE} bytes
 * exchange: the host sends one request and reads its one reply; 115200 baud, 8N1
 *
 * request                  reply              meaning
 * HELLO                    LINEBOT 1          identity and protocol version
 * ZERO                     OK                 both encoder counts to 0
 * SPEED m dps              OK                 motor m (A, B) at dps degrees per second, -1000..1000
 * STOP m BRAKE|COAST       OK                 motor m stopped, braking (held) or coasting (free)
 * COUNT                    COUNT a b          encoder degrees of A and B since ZERO, signed
 * READ i                   VALUE i v          input i (1, 2): a ranger's centimetres, a switch's 0 or 1
 * (refused)                ERR code text      code 1: unknown command, 2: bad argument, 3: bad port
 *
 * watchdog: the board stops both motors when it hears no request for {@value #WATCHDOG_MILLIS} ms
 * </pre>
 *
 * Stateless: every method builds a request line or reads a reply line.
 */
public final class LineBotProtocol {

    /** The protocol version this codec speaks ({@code LINEBOT 1}). */
    public static final int VERSION = 1;
    /** The longest line, LF included. */
    public static final int MAX_LINE = 64;
    /** How long the board keeps its motors running without hearing a request. */
    public static final int WATCHDOG_MILLIS = 1000;
    /** The fastest speed the board takes, degrees per second either way. */
    public static final int MAX_DEGREES_PER_SECOND = 1000;
    /** The line end. */
    public static final byte LF = 0x0A;

    /** The codes of {@code ERR} replies. */
    public enum Error {
        /** The board does not know the command. */
        UNKNOWN_COMMAND(1),
        /** An argument is missing, not a number, or out of range. */
        BAD_ARGUMENT(2),
        /** The board has no such motor or input. */
        BAD_PORT(3);

        private final int code;

        Error(int code) {
            this.code = code;
        }

        /** @return its number on the wire */
        public int code() {
            return code;
        }

        /**
         * @param code a code from an {@code ERR} reply
         * @return its error
         * @throws IllegalArgumentException naming the code if the protocol has none such
         */
        public static Error fromCode(int code) {
            for (Error e : values()) {
                if (e.code == code) {
                    return e;
                }
            }
            throw new IllegalArgumentException("LineBot error code " + code + " is none of the protocol's (1, 2, 3)");
        }
    }

    private LineBotProtocol() {
    }

    /**
     * @param port a motor port
     * @return it, checked
     * @throws IllegalArgumentException if the LineBot has no such motor
     */
    public static String motor(String port) {
        if (!port.equals("A") && !port.equals("B")) {
            throw new IllegalArgumentException("the LineBot has motor ports A and B, not '" + port + "'");
        }
        return port;
    }

    /**
     * @param port an input port, {@code 1} or {@code 2}
     * @return its number
     * @throws IllegalArgumentException if the LineBot has no such input
     */
    public static int input(String port) {
        return switch (port) {
            case "1" -> 1;
            case "2" -> 2;
            default -> throw new IllegalArgumentException("the LineBot has inputs 1 and 2, not '" + port + "'");
        };
    }

    /** @return HELLO */
    public static String hello() {
        return "HELLO";
    }

    /** @return ZERO */
    public static String zero() {
        return "ZERO";
    }

    /** @return COUNT */
    public static String count() {
        return "COUNT";
    }

    /**
     * @param port             A or B
     * @param degreesPerSecond the speed, rounded to a whole degree a second and kept within ±1000
     * @return SPEED
     */
    public static String speed(String port, double degreesPerSecond) {
        long dps = Math.max(-MAX_DEGREES_PER_SECOND, Math.min(MAX_DEGREES_PER_SECOND, Math.round(degreesPerSecond)));
        if (dps == 0 && degreesPerSecond != 0) {
            dps = degreesPerSecond > 0 ? 1 : -1; // the slowest speed, rather than none
        }
        return "SPEED " + motor(port) + " " + dps;
    }

    /**
     * @param port  A or B
     * @param brake whether the motor is held (BRAKE) or let run down (COAST)
     * @return STOP
     */
    public static String stop(String port, boolean brake) {
        return "STOP " + motor(port) + (brake ? " BRAKE" : " COAST");
    }

    /**
     * @param input 1 or 2
     * @return READ
     */
    public static String read(int input) {
        return "READ " + input;
    }

    /**
     * @param reply a reply line, without its LF
     * @return the error it reports, or {@code null} if it is not an {@code ERR} reply
     * @throws IllegalArgumentException if it is an {@code ERR} reply that does not parse
     */
    public static Refusal refusal(String reply) {
        if (!reply.startsWith("ERR ")) {
            return null;
        }
        String[] f = reply.split(" ", 3);
        if (f.length < 3) {
            throw new IllegalArgumentException("an ERR reply has a code and a text, got '" + reply + "'");
        }
        return new Refusal(Error.fromCode(number(reply, f[1])), f[2]);
    }

    /**
     * An {@code ERR} reply.
     *
     * @param error its code
     * @param text  what the board said
     */
    public record Refusal(Error error, String text) {
    }

    /**
     * @param reply a reply line
     * @return the protocol version of a {@code LINEBOT v} reply
     * @throws IllegalArgumentException if it is not one
     */
    public static int version(String reply) {
        String[] f = fields(reply, "LINEBOT", 2);
        return number(reply, f[1]);
    }

    /**
     * @param reply a reply line
     * @return A's and B's counts of a {@code COUNT a b} reply
     * @throws IllegalArgumentException if it is not one
     */
    public static int[] counts(String reply) {
        String[] f = fields(reply, "COUNT", 3);
        return new int[] {number(reply, f[1]), number(reply, f[2])};
    }

    /**
     * @param reply a reply line
     * @param input the input asked for
     * @return the value of a {@code VALUE i v} reply for that input
     * @throws IllegalArgumentException if it is not one
     */
    public static int value(String reply, int input) {
        String[] f = fields(reply, "VALUE", 3);
        if (number(reply, f[1]) != input) {
            throw new IllegalArgumentException("expected the value of input " + input + ", got '" + reply + "'");
        }
        return number(reply, f[2]);
    }

    /**
     * @param reply a reply line
     * @throws IllegalArgumentException if it is not {@code OK}
     */
    public static void ok(String reply) {
        if (!reply.equals("OK")) {
            throw new IllegalArgumentException("expected OK, got '" + reply + "'");
        }
    }

    private static String[] fields(String reply, String keyword, int count) {
        String[] f = reply.split(" ");
        if (f.length != count || !f[0].equals(keyword)) {
            throw new IllegalArgumentException(String.format(Locale.ROOT, "expected a %s reply of %d fields, got '%s'", keyword, count, reply));
        }
        return f;
    }

    private static int number(String reply, String field) {
        try {
            return Integer.parseInt(field);
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("'" + field + "' in '" + reply + "' is not a whole number", e);
        }
    }
}
