package io.robomw.platform.aibo;

import java.nio.charset.StandardCharsets;
import java.util.Objects;
import java.util.OptionalDouble;

/**
 * One message of an URBI server, as {@link UrbiReplyDecoder} reads it.
 *
 * @param timestamp the server's clock, milliseconds since it started
 * @param tag       the tag of the command that caused it, or empty for an untagged message
 * @param kind      what it is
 * @param text      the payload after the header: for {@link Kind#SYSTEM} and {@link Kind#ERROR}
 *                  without the {@code ***}/{@code !!!} prefix and the space after it; for
 *                  {@link Kind#BINARY} the header's keywords after the length
 * @param data      the bytes of a {@link Kind#BINARY} message; empty for the others
 */
public record UrbiReply(long timestamp, String tag, Kind kind, String text, byte[] data) {

    /** What a message is, from the start of its payload. */
    public enum Kind {
        /** {@code *** text}: a system message (the banner, {@code end}, {@code pong}). */
        SYSTEM,
        /** {@code !!! text}: an error. */
        ERROR,
        /** {@code BIN n keywords}, then n bytes: binary data (a camera image, sound). */
        BINARY,
        /** Anything else: a value (a number, a string, a list). */
        VALUE
    }

    /** Checks and copies. */
    public UrbiReply {
        Objects.requireNonNull(tag, "tag");
        Objects.requireNonNull(kind, "kind");
        Objects.requireNonNull(text, "text");
        data = data == null ? new byte[0] : data.clone();
    }

    /** @return the bytes of a binary message (a copy) */
    @Override
    public byte[] data() {
        return data.clone();
    }

    /** @return whether the message has a tag */
    public boolean tagged() {
        return !tag.isEmpty();
    }

    /** @return whether it is the {@code *** end} message of a command sent with {@code +end} */
    public boolean isEnd() {
        return kind == Kind.SYSTEM && text.equals(UrbiProtocol.END_MESSAGE);
    }

    /**
     * @return the value as a number, if it is a finite number ({@code 421.000000}, {@code -3.5e-05})
     */
    public OptionalDouble number() {
        if (kind != Kind.VALUE) {
            return OptionalDouble.empty();
        }
        String t = text.strip();
        if (t.isEmpty() || t.length() > 64 || !t.matches("[-+]?(\\d+\\.?\\d*|\\.\\d+)([eE][-+]?\\d{1,4})?")) {
            return OptionalDouble.empty();
        }
        double d = Double.parseDouble(t);
        return Double.isFinite(d) ? OptionalDouble.of(d) : OptionalDouble.empty();
    }

    /** @return the message as the server wrote it (binary data as its length), for messages and logs */
    public String describe() {
        String payload = switch (kind) {
            case SYSTEM -> UrbiProtocol.SYSTEM_PREFIX + " " + text;
            case ERROR -> UrbiProtocol.ERROR_PREFIX + " " + text;
            case BINARY -> UrbiProtocol.BINARY_KEYWORD + " " + data.length + (text.isEmpty() ? "" : " " + text);
            case VALUE -> text;
        };
        return "[" + String.format("%08d", timestamp) + (tagged() ? ":" + tag : "") + "] " + payload;
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof UrbiReply r && r.timestamp == timestamp && r.tag.equals(tag) && r.kind == kind && r.text.equals(text)
                && java.util.Arrays.equals(r.data, data);
    }

    @Override
    public int hashCode() {
        return Objects.hash(timestamp, tag, kind, text, java.util.Arrays.hashCode(data));
    }

    @Override
    public String toString() {
        return describe() + (kind == Kind.BINARY ? " " + new String(data, StandardCharsets.ISO_8859_1) : "");
    }
}
