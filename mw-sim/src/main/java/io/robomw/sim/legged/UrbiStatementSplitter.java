package io.robomw.sim.legged;

import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Cuts an URBI client's byte stream into top-level statements: text up to a terminator
 * ({@code ;} {@code ,} {@code |} {@code &}) that is outside braces, parentheses, strings and
 * comments ({@code //}, {@code /* *}{@code /} and {@code #} to the end of the line, as the URBI
 * kernel's command queue skips them). A decoder of bytes from outside: whatever it is fed, it
 * neither throws nor grows without bound.
 *
 * <h2>The emergency escape {@code $$}</h2>
 * As in the URBI 1.x kernel ({@code UCommandQueue::popCommand} in {@code ucommandqueue.cc}, and
 * {@code UConnection::received}, which then clears its receive queue): two dollar signs outside a
 * string and a comment, at any depth of braces and parentheses, abandon the statement being read
 * and everything received with them after them, silently; cutting starts afresh with the next
 * bytes the client sends. A statement held open by an unclosed brace, whose text would otherwise
 * swallow everything the client sends after it, can so be abandoned by the client. Statements
 * completed before the {@code $$} stand. The two must come in one read, as the kernel looks for
 * the second only among the bytes it has received; the bytes of a binary value are not scanned.
 *
 * <ul>
 *   <li>A statement longer than {@code maxStatementBytes} is reported and skipped up to the next
 *   newline, where cutting starts afresh.</li>
 *   <li>A closing brace or parenthesis without its opening one is reported at once and the text
 *   so far dropped.</li>
 *   <li>A byte outside printable ASCII (other than tab, carriage return and newline) becomes
 *   U+FFFD, which the parser refuses with a clear error.</li>
 *   <li>A statement that assigns a binary value ({@code speaker.val = BIN 1024 raw;}) is followed
 *   by that many raw bytes, which are counted and skipped, not read as text, so the stream keeps
 *   its framing.</li>
 * </ul>
 * Not thread-safe: one reader feeds it.
 */
public final class UrbiStatementSplitter {

    /** Default longest statement: 64 KiB. */
    public static final int DEFAULT_MAX_STATEMENT_BYTES = 64 * 1024;

    private static final Pattern BINARY = Pattern.compile("=\\s*BIN\\s+(\\d{1,12})\\b");

    /** Told of each statement and each error. */
    public interface Listener {
        /**
         * @param text       the statement, without its terminator, stripped
         * @param terminator the terminator that ended it
         */
        void statement(String text, char terminator);

        /**
         * @param message what was wrong
         */
        void error(String message);
    }

    private final int maxStatementBytes;
    private final StringBuilder text = new StringBuilder();
    private int depth;
    private boolean inString;
    private boolean escape;
    private boolean lineComment;
    private boolean blockComment;
    private boolean skipToNewline;
    private long binaryRemaining;
    private char previous;
    private long escapes;

    /** A splitter with the default limit. */
    public UrbiStatementSplitter() {
        this(DEFAULT_MAX_STATEMENT_BYTES);
    }

    /**
     * @param maxStatementBytes the longest statement accepted, at least 16
     */
    public UrbiStatementSplitter(int maxStatementBytes) {
        if (maxStatementBytes < 16) {
            throw new IllegalArgumentException("maxStatementBytes must be >= 16, got " + maxStatementBytes);
        }
        this.maxStatementBytes = maxStatementBytes;
    }

    /**
     * @param buf      bytes from the client
     * @param off      the first
     * @param len      how many
     * @param listener told of each statement and error, in order
     */
    public void feed(byte[] buf, int off, int len, Listener listener) {
        java.util.Objects.checkFromIndexSize(off, len, buf.length);
        int end = off + len;
        for (int i = off; i < end; i++) {
            int b = buf[i] & 0xFF;
            if (binaryRemaining > 0) {
                binaryRemaining--;
                continue;
            }
            if (b == '$' && i + 1 < end && buf[i + 1] == '$' && !inString && !lineComment && !blockComment) {
                emergencyEscape();
                return; // the kernel clears its whole receive queue: what came after the $$ goes too
            }
            if (skipToNewline) {
                if (b == '\n') {
                    skipToNewline = false;
                }
                continue;
            }
            char c = b == '\t' || b == '\r' || b == '\n' || (b >= 32 && b < 127) ? (char) b : '\uFFFD';
            accept(c, listener);
            previous = c;
        }
    }

    private void accept(char c, Listener listener) {
        if (lineComment) {
            if (c == '\n') {
                lineComment = false;
                append(' ', listener);
            }
            return;
        }
        if (blockComment) {
            if (c == '/' && previous == '*') {
                blockComment = false;
                previous = ' ';
                append(' ', listener);
            }
            return;
        }
        if (inString) {
            append(c, listener);
            if (escape) {
                escape = false;
            } else if (c == '\\') {
                escape = true;
            } else if (c == '"' || c == '\n') {
                inString = false;
            }
            return;
        }
        switch (c) {
            case '"' -> {
                inString = true;
                append(c, listener);
            }
            case '/' -> {
                if (previous == '/' && endsWith('/')) {
                    text.setLength(text.length() - 1);
                    lineComment = true;
                } else {
                    append(c, listener);
                }
            }
            case '*' -> {
                if (previous == '/' && endsWith('/')) {
                    text.setLength(text.length() - 1);
                    blockComment = true;
                    previous = ' ';
                } else {
                    append(c, listener);
                }
            }
            case '#' -> lineComment = true;
            case '{', '(' -> {
                depth++;
                append(c, listener);
            }
            case '}', ')' -> {
                if (depth == 0) {
                    listener.error("'" + c + "' closes nothing in \"" + excerpt(text + String.valueOf(c)) + "\"");
                    reset();
                    return;
                }
                depth--;
                append(c, listener);
            }
            case ';', ',', '|', '&' -> {
                if (depth > 0) {
                    append(c, listener);
                } else {
                    emit(c, listener);
                }
            }
            default -> append(c, listener);
        }
    }

    private boolean endsWith(char c) {
        return !text.isEmpty() && text.charAt(text.length() - 1) == c;
    }

    private void append(char c, Listener listener) {
        if (text.length() >= maxStatementBytes) {
            listener.error("a statement longer than " + maxStatementBytes + " bytes: \"" + excerpt(text) + "\"; skipped to the next line");
            reset();
            skipToNewline = c != '\n';
            return;
        }
        text.append(c);
    }

    private void emit(char terminator, Listener listener) {
        String statement = text.toString().strip();
        reset();
        if (statement.isEmpty()) {
            return;
        }
        Matcher m = BINARY.matcher(statement);
        if (m.find()) {
            binaryRemaining = Long.parseLong(m.group(1));
        }
        listener.statement(statement, terminator);
    }

    /** The emergency escape: the statement being read is abandoned, and cutting starts afresh. */
    private void emergencyEscape() {
        reset();
        skipToNewline = false;
        previous = ' ';
        escapes++;
    }

    /** @return how many times the client used the emergency escape {@code $$} */
    public long escapes() {
        return escapes;
    }

    private void reset() {
        text.setLength(0);
        depth = 0;
        inString = false;
        escape = false;
        lineComment = false;
        blockComment = false;
    }

    /** @return whether a statement has begun and not yet ended, or a comment, or a binary value's bytes */
    public boolean midStatement() {
        return !text.toString().isBlank() || binaryRemaining > 0 || skipToNewline || lineComment || blockComment;
    }

    static String excerpt(CharSequence s) {
        String t = s.toString().strip().replace('\n', ' ').replace('\r', ' ').replace('\t', ' ');
        return t.length() > 60 ? t.substring(0, 60) + "..." : t;
    }
}
