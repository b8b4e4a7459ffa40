package io.robomw.agents.messaging;

import java.nio.charset.StandardCharsets;
import java.time.Instant;
import java.time.format.DateTimeParseException;
import java.util.ArrayList;
import java.util.List;

/**
 * What a messaging node announces about itself where others can look it up (an MQTT broker keeps
 * it retained, and its will replaces it with the offline version when the node is gone): its
 * name, whether it is online, where it receives, and what it serves.
 *
 * <p>Stored format, version {@value #VERSION}: UTF-8 text, one field a line, {@code KEY VALUE},
 * in this order; at most {@value #MAX_BYTES} bytes. Values never contain a line break.
 * <pre>
 * robomw-presence 2
 * node NAME
 * status online|offline
 * time 2026-11-24T10:15:30.123Z        (when this version was made)
 * since 2026-11-24T10:15:29.870Z       (zero or one: when the node's connection to the broker began, its will's time;
 *                                       every record of one connection, its will included, carries the same)
 * client MQTT-CLIENT-ID                 (empty when not announced through a broker)
 * session-expiry SECONDS                (how long the broker keeps the node's session when it is away; 0 = clean)
 * messaging ADDRESS                     (zero or more: where the node receives)
 * host NAME AGENT-HOST-ADDRESS          (zero or one: the agent host the node belongs to)
 * robot NAME                            (zero or more: robots it serves, Robots.remote)
 * agent DESCRIPTION                     (zero or more: agents on its host, "ID CLASS STATUS")
 * sig SIGNATURE                         (zero or one, last: PresenceSeal's HMAC-SHA256 over every byte before this line)
 * </pre>
 * Version 2 added the {@code since} and {@code sig} lines; version 1 records (neither) are still
 * read, their {@code since} being their {@code time}. Decoding
 * refuses another version, an unknown key, a missing field, a {@code sig} line that is not the
 * last and an oversized record, naming what is wrong. Readers with the cluster's
 * {@link PresenceSeal} take only records it signed ({@link #decodeSealed}).
 *
 * @param node      the node's name
 * @param online    whether it is up
 * @param time      when this version was made
 * @param since     when the node's connection to the broker began (the time of its will): a reader takes no record of an
 *                  earlier connection of the same client after one of a later (as Sparkplug ties a death to its birth)
 * @param client    the MQTT client identifier it announced through, or empty
 * @param sessionExpirySeconds how long the broker keeps its session while it is away (0: a clean session,
 *                  nothing is kept for it)
 * @param messaging where it receives
 * @param host      the agent host's name, or {@code null}
 * @param hostAddress the agent host's address, or {@code null}
 * @param robots    robots it serves
 * @param agents    agents on its host
 */
public record PresenceRecord(String node, boolean online, Instant time, Instant since, String client, long sessionExpirySeconds, List<String> messaging, String host,
                             String hostAddress, List<String> robots, List<String> agents) {

    /** The version this class writes (it also reads version 1, which had no signature). */
    public static final int VERSION = 2;
    /** The key of the signature line. */
    public static final String SIGNATURE_KEY = "sig";
    /** The first line's key. */
    public static final String MAGIC = "robomw-presence";
    /** The largest record accepted. */
    public static final int MAX_BYTES = 65_536;

    /** Checks and copies. */
    public PresenceRecord {
        oneLine("node", node);
        java.util.Objects.requireNonNull(time, "time");
        java.util.Objects.requireNonNull(since, "since");
        oneLine("client", client);
        if (sessionExpirySeconds < 0) {
            throw new IllegalArgumentException("session expiry must be >= 0 seconds, got " + sessionExpirySeconds);
        }
        messaging = List.copyOf(messaging);
        robots = List.copyOf(robots);
        agents = List.copyOf(agents);
        messaging.forEach(m -> oneLine("messaging", m));
        robots.forEach(r -> oneLine("robot", r));
        agents.forEach(a -> oneLine("agent", a));
        if ((host == null) != (hostAddress == null)) {
            throw new IllegalArgumentException("a presence names an agent host with both its name and its address, got " + host + " and " + hostAddress);
        }
        if (host != null) {
            oneLine("host", host);
            oneLine("host address", hostAddress);
            if (hostAddress.isEmpty() || hostAddress.contains(" ")) {
                throw new IllegalArgumentException("agent host address '" + hostAddress + "' must be one word");
            }
        }
    }

    /** @return this record with {@code online} false and the time now */
    public PresenceRecord offline(Instant now) {
        return new PresenceRecord(node, false, now, since, client, sessionExpirySeconds, messaging, host, hostAddress, robots, agents);
    }

    /**
     * @param seal the cluster's seal, or {@code null} for an unsigned record
     * @return the stored format, signed with the seal
     */
    public byte[] encode(io.robomw.agents.messaging.security.PresenceSeal seal) {
        byte[] unsigned = encode();
        if (seal == null) {
            return unsigned;
        }
        byte[] line = (SIGNATURE_KEY + " " + seal.sign(unsigned) + "\n").getBytes(StandardCharsets.UTF_8);
        byte[] out = java.util.Arrays.copyOf(unsigned, unsigned.length + line.length);
        System.arraycopy(line, 0, out, unsigned.length, line.length);
        return out;
    }

    /**
     * Decodes a record and checks its signature.
     *
     * @param bytes a stored record
     * @param where where it came from, for the error
     * @param seal  the cluster's seal
     * @return the record, or empty if it is unsigned or not signed with the seal's key (to be ignored and counted)
     * @throws IllegalArgumentException naming what is wrong if it is not a presence record at all
     */
    public static java.util.Optional<PresenceRecord> decodeSealed(byte[] bytes, String where, io.robomw.agents.messaging.security.PresenceSeal seal) {
        PresenceRecord record = decode(bytes, where);
        String text = new String(bytes, StandardCharsets.UTF_8);
        int at = text.lastIndexOf("\n" + SIGNATURE_KEY + " ");
        if (at < 0) {
            return java.util.Optional.empty();
        }
        byte[] signed = text.substring(0, at + 1).getBytes(StandardCharsets.UTF_8);
        String signature = text.substring(at + 2 + SIGNATURE_KEY.length()).strip();
        return seal.verify(signed, signature) ? java.util.Optional.of(record) : java.util.Optional.empty();
    }

    /** @return the stored format, unsigned */
    public byte[] encode() {
        StringBuilder b = new StringBuilder(256);
        b.append(MAGIC).append(' ').append(VERSION).append('\n');
        b.append("node ").append(node).append('\n');
        b.append("status ").append(online ? "online" : "offline").append('\n');
        b.append("time ").append(time).append('\n');
        b.append("since ").append(since).append('\n');
        b.append("client ").append(client).append('\n');
        b.append("session-expiry ").append(sessionExpirySeconds).append('\n');
        messaging.forEach(m -> b.append("messaging ").append(m).append('\n'));
        if (host != null) {
            b.append("host ").append(host).append(' ').append(hostAddress).append('\n');
        }
        robots.forEach(r -> b.append("robot ").append(r).append('\n'));
        agents.forEach(a -> b.append("agent ").append(a).append('\n'));
        byte[] bytes = b.toString().getBytes(StandardCharsets.UTF_8);
        if (bytes.length > MAX_BYTES) {
            throw new IllegalArgumentException("presence of node '" + node + "' is " + bytes.length + " bytes, above " + MAX_BYTES
                    + "; it lists " + agents.size() + " agents and " + robots.size() + " robots");
        }
        return bytes;
    }

    /**
     * @param bytes a stored record
     * @param where where it came from, for the error
     * @return the record
     * @throws IllegalArgumentException naming what is wrong
     */
    public static PresenceRecord decode(byte[] bytes, String where) {
        if (bytes.length > MAX_BYTES) {
            throw new IllegalArgumentException(where + ": presence of " + bytes.length + " bytes, above " + MAX_BYTES);
        }
        String[] lines = new String(bytes, StandardCharsets.UTF_8).split("\n", -1);
        if (lines.length == 0 || !lines[0].equals(MAGIC + " " + VERSION) && !lines[0].equals(MAGIC + " 1")) {
            String first = lines.length == 0 ? "" : lines[0];
            throw new IllegalArgumentException(where + ": not a RoboMW presence of version 1 or " + VERSION + " (first line '"
                    + (first.length() > 40 ? first.substring(0, 40) + "..." : first) + "')");
        }
        String node = null;
        Boolean online = null;
        Instant time = null;
        Instant since = null;
        String client = null;
        Long expiry = null;
        String host = null;
        String hostAddress = null;
        List<String> messaging = new ArrayList<>();
        List<String> robots = new ArrayList<>();
        List<String> agents = new ArrayList<>();
        for (int i = 1; i < lines.length; i++) {
            String line = lines[i];
            if (line.isEmpty() && i == lines.length - 1) {
                break;
            }
            int space = line.indexOf(' ');
            String key = space < 0 ? line : line.substring(0, space);
            String value = space < 0 ? "" : line.substring(space + 1);
            switch (key) {
                case "node" -> node = value;
                case "status" -> online = switch (value) {
                    case "online" -> true;
                    case "offline" -> false;
                    default -> throw new IllegalArgumentException(where + ": line " + (i + 1) + ": status '" + value + "' is neither online nor offline");
                };
                case "time" -> {
                    try {
                        time = Instant.parse(value);
                    } catch (DateTimeParseException e) {
                        throw new IllegalArgumentException(where + ": line " + (i + 1) + ": time '" + value + "' is not an ISO-8601 instant");
                    }
                }
                case "since" -> {
                    try {
                        since = Instant.parse(value);
                    } catch (DateTimeParseException e) {
                        throw new IllegalArgumentException(where + ": line " + (i + 1) + ": since '" + value + "' is not an ISO-8601 instant");
                    }
                }
                case "client" -> client = value;
                case "session-expiry" -> {
                    try {
                        expiry = Long.parseLong(value);
                    } catch (NumberFormatException e) {
                        throw new IllegalArgumentException(where + ": line " + (i + 1) + ": session-expiry '" + value + "' is not a number of seconds");
                    }
                }
                case "messaging" -> messaging.add(value);
                case "host" -> {
                    int last = value.lastIndexOf(' ');
                    if (last <= 0) {
                        throw new IllegalArgumentException(where + ": line " + (i + 1) + ": 'host' needs a name and an address");
                    }
                    host = value.substring(0, last);
                    hostAddress = value.substring(last + 1);
                }
                case "robot" -> robots.add(value);
                case "agent" -> agents.add(value);
                case SIGNATURE_KEY -> {
                    if (i < lines.length - 2 || (i == lines.length - 2 && !lines[i + 1].isEmpty())) {
                        throw new IllegalArgumentException(where + ": line " + (i + 1) + ": the signature must be the last line");
                    }
                }
                default -> throw new IllegalArgumentException(where + ": line " + (i + 1) + ": unknown key '" + key + "' in a presence of version " + VERSION);
            }
        }
        if (node == null || node.isEmpty() || online == null || time == null || client == null || expiry == null) {
            throw new IllegalArgumentException(where + ": a presence needs node, status, time, client and session-expiry lines");
        }
        return new PresenceRecord(node, online, time, since == null ? time : since, client, expiry, messaging, host, hostAddress, robots, agents);
    }

    private static void oneLine(String what, String value) {
        if (value == null) {
            throw new IllegalArgumentException("presence " + what + " is missing");
        }
        if (value.indexOf('\n') >= 0 || value.indexOf('\r') >= 0) {
            throw new IllegalArgumentException("presence " + what + " '" + value.replace("\n", "\\n") + "' must not contain a line break");
        }
    }
}
