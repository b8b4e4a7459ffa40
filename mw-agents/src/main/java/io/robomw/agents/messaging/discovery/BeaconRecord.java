package io.robomw.agents.messaging.discovery;

import java.nio.ByteBuffer;
import java.nio.charset.CharacterCodingException;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;

/**
 * What a messaging node's discovery beacon says about it, once a period, on a multicast group:
 * its name, where it receives, the topics it listens to and publishes on, the robots it serves.
 * {@code mw nodes}, {@code mw topics} and {@code mw msg echo} read it.
 *
 * <p>Wire format, version {@value #VERSION}: the payload (text) of a publication on topic
 * {@value #TOPIC}: UTF-8, one field a line, {@code KEY VALUE}, in this order; at most
 * {@value #MAX_BYTES} bytes (lists are cut to fit, and {@code truncated yes} says so). Every line,
 * the last one too, ends with a line break ({@code \n}); values are never empty and never contain
 * a line break or a carriage return.
 * <pre>
 * robomw-beacon 1
 * node NAME
 * status online|offline            (offline: the node is closing)
 * period-ms N                      (the next beacon comes within this)
 * host NAME AGENT-HOST-ADDRESS     (zero or one)
 * messaging ADDRESS                (zero or more: where the node receives)
 * listens TOPIC                    (zero or more)
 * publishes TOPIC                  (zero or more)
 * robot NAME                       (zero or more: robots it serves, Robots.remote)
 * truncated yes                    (zero or one: lists were cut to fit)
 * </pre>
 * Decoding refuses another version, bytes that are not UTF-8, a record cut short (its last line
 * without its line break), an unknown key, an empty value, a missing field and an oversized record,
 * naming the sender and what is wrong (a decoder of outside bytes: fuzzed). What it accepts is
 * written back as it was read: a record read from at most {@value #MAX_BYTES} bytes is encoded
 * whole, without cutting its lists.
 *
 * @param node      the node's name
 * @param online    whether it is up (false in its last beacon)
 * @param periodMillis when the next beacon comes, at the latest
 * @param host      its agent host's name, or {@code null}
 * @param hostAddress its agent host's address, or {@code null}
 * @param messaging where it receives
 * @param listens   topics it listens to or subscribes to
 * @param publishes topics it has published on
 * @param robots    robots it serves
 * @param truncated whether lists were cut to fit one datagram
 */
public record BeaconRecord(String node, boolean online, long periodMillis, String host, String hostAddress, List<String> messaging,
                           List<String> listens, List<String> publishes, List<String> robots, boolean truncated) {

    /** The version this class reads and writes. */
    public static final int VERSION = 1;
    /** The first line's key. */
    public static final String MAGIC = "robomw-beacon";
    /** The topic beacons are published on. */
    public static final String TOPIC = "robomw/beacon";
    /** The largest record: one datagram, well inside any link's MTU chain. */
    public static final int MAX_BYTES = 8192;
    private static final String TRUNCATED_LINE = "truncated yes\n";

    /** Checks and copies. */
    public BeaconRecord {
        oneLine("node", node);
        if (periodMillis <= 0) {
            throw new IllegalArgumentException("beacon period must be > 0 ms, got " + periodMillis);
        }
        if ((host == null) != (hostAddress == null)) {
            throw new IllegalArgumentException("a beacon names an agent host with both its name and its address");
        }
        messaging = List.copyOf(messaging);
        listens = List.copyOf(listens);
        publishes = List.copyOf(publishes);
        robots = List.copyOf(robots);
        for (List<String> l : List.of(messaging, listens, publishes, robots)) {
            l.forEach(v -> oneLine("value", v));
        }
    }

    /** @return the wire format; lists are cut (and {@code truncated yes} added) when the whole would not fit {@link #MAX_BYTES} */
    public byte[] encode() {
        StringBuilder b = new StringBuilder(256);
        b.append(MAGIC).append(' ').append(VERSION).append('\n');
        b.append("node ").append(node).append('\n');
        b.append("status ").append(online ? "online" : "offline").append('\n');
        b.append("period-ms ").append(periodMillis).append('\n');
        if (host != null) {
            b.append("host ").append(host).append(' ').append(hostAddress).append('\n');
        }
        boolean cut = truncated;
        String[] keys = {"messaging", "listens", "publishes", "robot"};
        List<List<String>> lists = List.of(messaging, listens, publishes, robots);
        int size = utf8(b);
        int whole = size + (truncated ? TRUNCATED_LINE.length() : 0);
        for (int k = 0; k < keys.length; k++) {
            for (String v : lists.get(k)) {
                whole += utf8(keys[k] + " " + v + "\n");
            }
        }
        // only a record that does not fit is cut, leaving room to say so
        int budget = whole <= MAX_BYTES ? Integer.MAX_VALUE : MAX_BYTES - TRUNCATED_LINE.length();
        for (int k = 0; k < keys.length; k++) {
            for (String v : lists.get(k)) {
                String line = keys[k] + " " + v + "\n";
                int bytes = utf8(line);
                if (size + bytes > budget) {
                    cut = true;
                    continue;
                }
                b.append(line);
                size += bytes;
            }
        }
        if (cut) {
            b.append(TRUNCATED_LINE);
        }
        return b.toString().getBytes(StandardCharsets.UTF_8);
    }

    private static int utf8(CharSequence s) {
        return s.toString().getBytes(StandardCharsets.UTF_8).length;
    }

    /**
     * @param bytes a beacon's payload
     * @param from  who sent it, for the error
     * @return the record
     * @throws IllegalArgumentException naming the sender and what is wrong
     */
    public static BeaconRecord decode(byte[] bytes, String from) {
        if (bytes.length > MAX_BYTES) {
            throw new IllegalArgumentException(from + ": beacon of " + bytes.length + " bytes, above " + MAX_BYTES);
        }
        String text;
        try {
            text = StandardCharsets.UTF_8.newDecoder().onMalformedInput(CodingErrorAction.REPORT).onUnmappableCharacter(CodingErrorAction.REPORT)
                    .decode(ByteBuffer.wrap(bytes)).toString();
        } catch (CharacterCodingException e) {
            throw new IllegalArgumentException(from + ": not a RoboMW beacon (its bytes are not UTF-8 text)");
        }
        String[] lines = text.split("\n", -1);
        if (!lines[0].equals(MAGIC + " " + VERSION)) {
            String first = lines[0].length() > 40 ? lines[0].substring(0, 40) + "..." : lines[0];
            throw new IllegalArgumentException(from + ": not a RoboMW beacon of version " + VERSION + " (first line '" + first + "')");
        }
        if (!text.endsWith("\n")) {
            throw new IllegalArgumentException(from + ": beacon cut short: its last line, " + lines.length + ", does not end with a line break");
        }
        String node = null;
        Boolean online = null;
        Long period = null;
        String host = null;
        String hostAddress = null;
        boolean truncated = false;
        List<String> messaging = new ArrayList<>();
        List<String> listens = new ArrayList<>();
        List<String> publishes = new ArrayList<>();
        List<String> robots = new ArrayList<>();
        for (int i = 1; i < lines.length; i++) {
            String line = lines[i];
            if (line.isEmpty() && i == lines.length - 1) {
                break;
            }
            int space = line.indexOf(' ');
            if (space <= 0) {
                throw new IllegalArgumentException(from + ": beacon line " + (i + 1) + " is not 'KEY VALUE'");
            }
            String key = line.substring(0, space);
            String value = line.substring(space + 1);
            if (value.isEmpty() || value.indexOf('\r') >= 0) {
                throw new IllegalArgumentException(from + ": beacon line " + (i + 1) + " ('" + (key.length() > 40 ? key.substring(0, 40) + "..." : key)
                        + "') has " + (value.isEmpty() ? "no value" : "a carriage return in its value"));
            }
            switch (key) {
                case "node" -> node = value;
                case "status" -> online = switch (value) {
                    case "online" -> true;
                    case "offline" -> false;
                    default -> throw new IllegalArgumentException(from + ": beacon status '" + (value.length() > 40 ? value.substring(0, 40) + "..." : value)
                            + "' is neither online nor offline");
                };
                case "period-ms" -> {
                    if (!value.matches("-?[0-9]{1,18}")) {
                        String shown = value.length() > 40 ? value.substring(0, 40) + "..." : value;
                        throw new IllegalArgumentException(from + ": beacon period-ms '" + shown + "' is not a number");
                    }
                    period = Long.parseLong(value);
                    if (period <= 0 || period > 3_600_000) {
                        throw new IllegalArgumentException(from + ": beacon period-ms " + period + " is not 1 to 3600000");
                    }
                }
                case "host" -> {
                    int s = value.indexOf(' ');
                    if (s <= 0 || s == value.length() - 1) {
                        throw new IllegalArgumentException(from + ": beacon host line is not 'host NAME ADDRESS'");
                    }
                    host = value.substring(0, s);
                    hostAddress = value.substring(s + 1);
                }
                case "messaging" -> messaging.add(value);
                case "listens" -> listens.add(value);
                case "publishes" -> publishes.add(value);
                case "robot" -> robots.add(value);
                case "truncated" -> truncated = value.equals("yes");
                default -> throw new IllegalArgumentException(from + ": unknown beacon key '" + (key.length() > 40 ? key.substring(0, 40) + "..." : key) + "'");
            }
        }
        if (node == null || online == null || period == null) {
            throw new IllegalArgumentException(from + ": beacon without " + (node == null ? "node" : online == null ? "status" : "period-ms"));
        }
        try {
            return new BeaconRecord(node, online, period, host, hostAddress, messaging, listens, publishes, robots, truncated);
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException(from + ": " + e.getMessage(), e);
        }
    }

    private static void oneLine(String what, String value) {
        if (value == null || value.isEmpty() || value.indexOf('\n') >= 0 || value.indexOf('\r') >= 0) {
            throw new IllegalArgumentException("a beacon's " + what + " must be one non-empty line, got '" + value + "'");
        }
    }
}
