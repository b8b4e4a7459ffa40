package io.robomw.platform.aibo;

import java.nio.charset.StandardCharsets;
import java.util.regex.Pattern;

/**
 * URBI 1.x as the Sony Aibo's URBI server (Gostai) speaks it over TCP: the constants of the wire
 * format, and the encoding of the client's commands. Replies are decoded by
 * {@link UrbiReplyDecoder}. See {@code shared/protocols/README.md} §5 and docs/platforms.md.
 *
 * <h2>Client to server</h2>
 * <pre>
 *   [tag[+flag...]:] command terminator
 *
 *   c12+end: { robot.walk(0.5, 0.15) },      run in the background, tagged c12, "*** end" when done
 *   r13: distanceNear.val,                   read a device; the value comes back tagged r13
 *   s3: every(100ms) accelX.val,             stream a device every 100 ms, tagged s3
 *   stop c12,                                end the command tagged c12
 * </pre>
 * ASCII text; a command ends with {@value #BACKGROUND} (the next one starts at once) or
 * {@value #SEQUENTIAL} (the next one waits for it). Whitespace and newlines between commands do
 * not matter; RoboMW ends each command with a newline, so wire logs read line by line. A tag is
 * 1 to {@value #MAX_TAG_LENGTH} letters, digits and underscores, starting with a letter; the flag
 * {@value #END_FLAG} asks for a {@code *** end} message when the command finishes. Every command
 * RoboMW sends is tagged, so every reply and error names the command it belongs to, and
 * high-level commands are sent as a block ({@code { ... }}) so that a template holding several
 * statements stays one tagged command.
 *
 * <h2>Server to client</h2>
 * <pre>
 *   '[' timestamp [':' tag] ']' ' ' payload '\n'
 *
 *   [00012345:r13] 421.000000                a value
 *   [00012346:c12] *** end                   a system message ({@value #SYSTEM_PREFIX})
 *   [00012347:c14] !!! unknown identifier: robot.fly     an error ({@value #ERROR_PREFIX})
 *   [00012348:img] BIN 6 raw 2 1\n + 6 bytes  binary data: header, newline, exactly that many bytes
 * </pre>
 * The timestamp is the server's clock in milliseconds since it started (liburbi reads it with
 * {@code [%d:%64[A-Za-z0-9_.]]}); untagged messages (the greeting banner) have no {@code :tag}.
 *
 * <h2>Sources</h2>
 * <ul>
 *   <li>URBI Language Specification v1.0 (J.-C. Baillie, January 2005), sections 1.2 (commands,
 *   tags, flags, messages) and 1.10 (stop, ping, motoron); URBI Server for Aibo ERS2xx ERS7,
 *   Introduction Manual v1.1 (July 2005): device names.</li>
 *   <li>The URBI SDK, {@code aldebaran/urbi} @12fe46e (AGPL; documents read, no code taken):
 *   {@code sdk-remote/include/urbi/uabstractclient.hh} ({@code URBI_PORT = 54000},
 *   {@code URBI_MAX_TAG_LENGTH = 64}), {@code sdk-remote/doc/liburbi.xml} (tags and callbacks,
 *   {@code "loop snd: micro.val,"}, {@code BIN} headers), {@code doc/guide/k1-to-k2.tex}
 *   ({@code tag+end}, {@code stop Foo}), {@code tests/2.x/k1-bin.chk} (a {@code BIN} value on the
 *   wire), {@code doc/specs/naming-standard.tex} (the Mobile interface: go, turn, stop, watchdog).</li>
 * </ul>
 */
public final class UrbiProtocol {

    /** The URBI server's TCP port. */
    public static final int TCP_PORT = 54000;
    /** The longest tag, characters. */
    public static final int MAX_TAG_LENGTH = 64;
    /** Ends a command that runs in the background: the next command starts at once. */
    public static final char BACKGROUND = ',';
    /** Ends a command the next one waits for. */
    public static final char SEQUENTIAL = ';';
    /** The tag flag that asks for a {@code *** end} message when the command finishes. */
    public static final String END_FLAG = "+end";
    /** The text of the system message {@link #END_FLAG} asks for. */
    public static final String END_MESSAGE = "end";
    /** Starts the payload of a system message. */
    public static final String SYSTEM_PREFIX = "***";
    /** Starts the payload of an error message. */
    public static final String ERROR_PREFIX = "!!!";
    /** The keyword of a binary value's header: {@code BIN <length> <keywords...>}. */
    public static final String BINARY_KEYWORD = "BIN";
    /** The startup command sent when no other is configured: switch the motors on. */
    public static final String DEFAULT_STARTUP = "motoron";

    private static final Pattern TAG = Pattern.compile("[A-Za-z][A-Za-z0-9_]{0," + (MAX_TAG_LENGTH - 1) + "}");

    private UrbiProtocol() {
    }

    /**
     * @param tag a tag
     * @return whether RoboMW may send it: a letter, then letters, digits and underscores, at most
     *         {@value #MAX_TAG_LENGTH} characters
     */
    public static boolean validTag(String tag) {
        return tag != null && TAG.matcher(tag).matches();
    }

    /**
     * A high-level command as one tagged background block that reports its end:
     * {@code tag+end: { text },} and a newline.
     *
     * @param tag  the tag
     * @param text the command, in URBI (one or several statements)
     * @return the bytes to send
     * @throws IllegalArgumentException if the tag is not valid or the text is not sendable
     */
    public static byte[] command(String tag, String text) {
        return line(requireTag(tag) + END_FLAG + ": { " + requireText(text) + " }" + BACKGROUND);
    }

    /**
     * A tagged read of a device's value: {@code tag: device.val,} and a newline.
     *
     * @param tag    the tag
     * @param device the device ({@code distanceNear}, {@code legLF1})
     * @return the bytes to send
     */
    public static byte[] read(String tag, String device) {
        return line(requireTag(tag) + ": " + requireDevice(device) + ".val" + BACKGROUND);
    }

    /**
     * A tagged stream of a device's value: {@code tag: every(Nms) device.val,} and a newline.
     *
     * @param tag      the tag
     * @param device   the device
     * @param periodMs how often, milliseconds, at least 1
     * @return the bytes to send
     */
    public static byte[] stream(String tag, String device, long periodMs) {
        if (periodMs < 1) {
            throw new IllegalArgumentException("a stream's period must be at least 1 ms, got " + periodMs);
        }
        return line(requireTag(tag) + ": every(" + periodMs + "ms) " + requireDevice(device) + ".val" + BACKGROUND);
    }

    /**
     * Ends the command of a tag: {@code stop tag,} and a newline.
     *
     * @param tag the tag
     * @return the bytes to send
     */
    public static byte[] stop(String tag) {
        return line("stop " + requireTag(tag) + BACKGROUND);
    }

    private static byte[] line(String text) {
        return (text + "\n").getBytes(StandardCharsets.US_ASCII);
    }

    private static String requireTag(String tag) {
        if (!validTag(tag)) {
            throw new IllegalArgumentException("URBI tag '" + tag + "' must be a letter then letters, digits or '_', at most " + MAX_TAG_LENGTH + " characters");
        }
        return tag;
    }

    private static String requireDevice(String device) {
        if (device == null || !device.matches("[A-Za-z_][A-Za-z0-9_.]*")) {
            throw new IllegalArgumentException("URBI device name '" + device + "' must be letters, digits, '_' and '.', starting with a letter");
        }
        return device;
    }

    private static String requireText(String text) {
        if (text == null || text.isBlank()) {
            throw new IllegalArgumentException("an URBI command must not be empty");
        }
        for (int i = 0; i < text.length(); i++) {
            char c = text.charAt(i);
            if (c > 126 || (c < 32 && c != '\t')) {
                throw new IllegalArgumentException(String.format("an URBI command is printable ASCII on one line; \"%s\" has character U+%04X at %d",
                        text, (int) c, i));
            }
        }
        return text.strip();
    }
}
