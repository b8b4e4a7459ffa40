package io.robomw.platform.aibo;

import java.io.ByteArrayOutputStream;
import java.nio.charset.StandardCharsets;

/**
 * Reads an URBI server's messages from its byte stream, however the stream splits or merges them:
 * feed it what arrives, and it hands over each whole message (see {@link UrbiProtocol} for the
 * format). A decoder of bytes from outside: nothing it is fed makes it throw or grow without
 * bound.
 *
 * <ul>
 *   <li>A line that is not a message (no {@code [timestamp]} or {@code [timestamp:tag]} header, a
 *   timestamp of more than 18 digits, a tag longer than {@value UrbiProtocol#MAX_TAG_LENGTH} or
 *   with other characters than letters, digits, {@code _} and {@code .}, a {@code BIN} header
 *   without a valid length) is reported to {@link Listener#malformed} and skipped; the next line
 *   is read as usual.</li>
 *   <li>A line longer than {@code maxLineBytes} is reported once and skipped up to its newline.</li>
 *   <li>A binary value longer than {@code maxBinaryBytes} is reported, and its bytes are skipped
 *   (they are counted, so the stream keeps its framing).</li>
 *   <li>Blank lines are ignored; a carriage return before the newline is dropped; text is UTF-8,
 *   invalid bytes become U+FFFD.</li>
 * </ul>
 *
 * <p>Not thread-safe: one reader feeds it.
 */
public final class UrbiReplyDecoder {

    /** Default longest line: 64 KiB. */
    public static final int DEFAULT_MAX_LINE_BYTES = 64 * 1024;
    /** Default longest binary value: 16 MiB (an ERS-7 camera image is about 150 KiB). */
    public static final int DEFAULT_MAX_BINARY_BYTES = 16 * 1024 * 1024;
    /** The most memory a binary value's header claims before its bytes come. */
    private static final int BINARY_CHUNK = 64 * 1024;
    /** The most digits a timestamp may have (milliseconds, so about 3 million years). */
    static final int MAX_TIMESTAMP_DIGITS = 18;

    /** Told of each message and of each malformed input. */
    public interface Listener {
        /**
         * @param reply a whole message
         */
        void reply(UrbiReply reply);

        /**
         * @param why     what was wrong
         * @param excerpt the start of the offending line (at most 80 characters), for logs
         */
        void malformed(String why, String excerpt);
    }

    private enum State { LINE, SKIP_LINE, BINARY }

    private final int maxLineBytes;
    private final int maxBinaryBytes;
    private final ByteArrayOutputStream line = new ByteArrayOutputStream(128);
    private State state = State.LINE;
    private long binaryRemaining;
    private ByteArrayOutputStream binary;
    private long binaryTimestamp;
    private String binaryTag;
    private String binaryKeywords;

    /** A decoder with the default limits. */
    public UrbiReplyDecoder() {
        this(DEFAULT_MAX_LINE_BYTES, DEFAULT_MAX_BINARY_BYTES);
    }

    /**
     * @param maxLineBytes   the longest line accepted, at least 16
     * @param maxBinaryBytes the longest binary value accepted, at least 0
     */
    public UrbiReplyDecoder(int maxLineBytes, int maxBinaryBytes) {
        if (maxLineBytes < 16 || maxBinaryBytes < 0) {
            throw new IllegalArgumentException("maxLineBytes must be >= 16 and maxBinaryBytes >= 0, got " + maxLineBytes + " and " + maxBinaryBytes);
        }
        this.maxLineBytes = maxLineBytes;
        this.maxBinaryBytes = maxBinaryBytes;
    }

    /**
     * Decodes what arrived.
     *
     * @param buf      the bytes
     * @param off      the first
     * @param len      how many
     * @param listener told of each whole message and each malformed line, in order
     */
    public void feed(byte[] buf, int off, int len, Listener listener) {
        java.util.Objects.checkFromIndexSize(off, len, buf.length);
        int i = off;
        int end = off + len;
        while (i < end) {
            switch (state) {
                case BINARY -> {
                    int n = (int) Math.min(binaryRemaining, end - i);
                    if (binary != null) {
                        binary.write(buf, i, n);
                    }
                    i += n;
                    binaryRemaining -= n;
                    if (binaryRemaining == 0) {
                        if (binary != null) {
                            listener.reply(new UrbiReply(binaryTimestamp, binaryTag, UrbiReply.Kind.BINARY, binaryKeywords, binary.toByteArray()));
                        }
                        binary = null;
                        state = State.LINE;
                    }
                }
                case SKIP_LINE -> {
                    if (buf[i++] == '\n') {
                        state = State.LINE;
                    }
                }
                case LINE -> {
                    byte b = buf[i++];
                    if (b == '\n') {
                        byte[] bytes = line.toByteArray();
                        line.reset();
                        parseLine(bytes, listener);
                    } else if (line.size() >= maxLineBytes) {
                        listener.malformed("a line longer than " + maxLineBytes + " bytes", excerpt(line.toByteArray()));
                        line.reset();
                        state = State.SKIP_LINE;
                    } else {
                        line.write(b);
                    }
                }
                default -> throw new IllegalStateException("state " + state);
            }
        }
    }

    /** Forgets a partial message: the stream starts anew (a new connection). */
    public void reset() {
        line.reset();
        binary = null;
        binaryRemaining = 0;
        state = State.LINE;
    }

    /** @return whether the decoder is in the middle of a message (a partial line or binary value) */
    public boolean midMessage() {
        return state != State.LINE || line.size() > 0;
    }

    private void parseLine(byte[] bytes, Listener listener) {
        int n = bytes.length;
        if (n > 0 && bytes[n - 1] == '\r') {
            n--;
        }
        String text = new String(bytes, 0, n, StandardCharsets.UTF_8);
        if (text.isBlank()) {
            return;
        }
        if (text.charAt(0) != '[') {
            listener.malformed("a message starts with '[timestamp]' or '[timestamp:tag]'", excerpt(text));
            return;
        }
        int close = text.indexOf(']');
        if (close < 0 || close > MAX_TIMESTAMP_DIGITS + UrbiProtocol.MAX_TAG_LENGTH + 3) {
            listener.malformed("the header '[timestamp:tag]' is not closed with ']'", excerpt(text));
            return;
        }
        String header = text.substring(1, close);
        int colon = header.indexOf(':');
        String digits = colon < 0 ? header : header.substring(0, colon);
        String tag = colon < 0 ? "" : header.substring(colon + 1);
        if (digits.isEmpty() || digits.length() > MAX_TIMESTAMP_DIGITS || !allDigits(digits)) {
            listener.malformed("the timestamp must be 1 to " + MAX_TIMESTAMP_DIGITS + " digits, got '" + digits + "'", excerpt(text));
            return;
        }
        if (colon >= 0 && (tag.isEmpty() || tag.length() > UrbiProtocol.MAX_TAG_LENGTH || !tagChars(tag))) {
            listener.malformed("the tag must be 1 to " + UrbiProtocol.MAX_TAG_LENGTH + " letters, digits, '_' or '.', got '" + tag + "'",
                    excerpt(text));
            return;
        }
        long timestamp = Long.parseLong(digits);
        String payload = text.substring(close + 1);
        if (payload.startsWith(" ")) {
            payload = payload.substring(1);
        }
        if (payload.startsWith(UrbiProtocol.SYSTEM_PREFIX)) {
            listener.reply(new UrbiReply(timestamp, tag, UrbiReply.Kind.SYSTEM, afterPrefix(payload), null));
        } else if (payload.startsWith(UrbiProtocol.ERROR_PREFIX)) {
            listener.reply(new UrbiReply(timestamp, tag, UrbiReply.Kind.ERROR, afterPrefix(payload), null));
        } else if (payload.equals(UrbiProtocol.BINARY_KEYWORD) || payload.startsWith(UrbiProtocol.BINARY_KEYWORD + " ")) {
            binaryHeader(timestamp, tag, payload, text, listener);
        } else {
            listener.reply(new UrbiReply(timestamp, tag, UrbiReply.Kind.VALUE, payload, null));
        }
    }

    private void binaryHeader(long timestamp, String tag, String payload, String text, Listener listener) {
        String[] words = payload.strip().split("\\s+", 3);
        if (words.length < 2 || words[1].isEmpty() || words[1].length() > 10 || !allDigits(words[1])) {
            listener.malformed("a binary value's header is 'BIN <length> [keywords]' with a decimal length", excerpt(text));
            return;
        }
        long length = Long.parseLong(words[1]);
        String keywords = words.length > 2 ? words[2] : "";
        if (length > maxBinaryBytes) {
            listener.malformed("a binary value of " + length + " bytes is longer than " + maxBinaryBytes + "; its bytes are skipped", excerpt(text));
            binary = null;
        } else {
            binary = new ByteArrayOutputStream((int) Math.min(length, BINARY_CHUNK)); // grows as the bytes come: a header alone claims at most 64 KiB
        }
        if (length == 0) {
            if (binary != null) {
                listener.reply(new UrbiReply(timestamp, tag, UrbiReply.Kind.BINARY, keywords, new byte[0]));
            }
            binary = null;
            return;
        }
        binaryTimestamp = timestamp;
        binaryTag = tag;
        binaryKeywords = keywords;
        binaryRemaining = length;
        state = State.BINARY;
    }

    private static String afterPrefix(String payload) {
        String rest = payload.substring(3);
        return rest.startsWith(" ") ? rest.substring(1) : rest;
    }

    private static boolean allDigits(String s) {
        for (int i = 0; i < s.length(); i++) {
            char c = s.charAt(i);
            if (c < '0' || c > '9') {
                return false;
            }
        }
        return true;
    }

    private static boolean tagChars(String s) {
        for (int i = 0; i < s.length(); i++) {
            char c = s.charAt(i);
            if (!(c >= 'A' && c <= 'Z' || c >= 'a' && c <= 'z' || c >= '0' && c <= '9' || c == '_' || c == '.')) {
                return false;
            }
        }
        return true;
    }

    private static String excerpt(byte[] bytes) {
        return excerpt(new String(bytes, 0, Math.min(bytes.length, 320), StandardCharsets.UTF_8));
    }

    private static String excerpt(String text) {
        String t = text.length() > 80 ? text.substring(0, 80) + "..." : text;
        StringBuilder sb = new StringBuilder(t.length());
        for (int i = 0; i < t.length(); i++) {
            char c = t.charAt(i);
            sb.append(c < 32 || c == 127 ? '?' : c);
        }
        return sb.toString();
    }
}
