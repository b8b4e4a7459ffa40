package io.robomw.platform.link;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.BufferedWriter;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.time.Clock;
import java.time.ZoneOffset;
import java.time.format.DateTimeFormatter;
import java.util.HexFormat;
import java.util.Objects;

/**
 * Appends every byte a {@link Communicator} sends or receives to a text file, one line per
 * transfer, flushed line by line so the file is complete even if the process dies:
 *
 * <pre>
 * 2026-11-21T19:05:01.123456Z &gt; 0C 00 00 04
 * 2026-11-21T19:05:01.131872Z &lt; 02 00 00
 * 2026-11-21T19:05:02.000010Z # link lost: serial /dev/pts/5: link lost: read failed ...
 * </pre>
 *
 * {@code >} is sent, {@code <} received, {@code #} a note from the communicator. Times are UTC
 * with microseconds. A received line holds what one read returned, so a frame may span lines.
 *
 * <p>Logging must never break the link: if the file cannot be written, one warning is logged and
 * further lines are dropped. Thread-safe; closed with its communicator.
 */
public final class WireLog implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(WireLog.class);

    private static final DateTimeFormatter TIMESTAMP =
            DateTimeFormatter.ofPattern("uuuu-MM-dd'T'HH:mm:ss.SSSSSS'Z'").withZone(ZoneOffset.UTC);
    private static final HexFormat HEX = HexFormat.ofDelimiter(" ").withUpperCase();

    private final Path file;
    private final Clock clock;
    private BufferedWriter writer;

    private WireLog(Path file, Clock clock, BufferedWriter writer) {
        this.file = file;
        this.clock = clock;
        this.writer = writer;
    }

    /**
     * Opens the file for appending, creating it if needed.
     *
     * @param file the log file
     * @return the log
     * @throws IOException if the file cannot be opened
     */
    public static WireLog open(Path file) throws IOException {
        return open(file, Clock.systemUTC());
    }

    /**
     * @param file  the log file
     * @param clock the source of timestamps (a fixed clock in tests)
     * @return the log
     * @throws IOException if the file cannot be opened
     */
    public static WireLog open(Path file, Clock clock) throws IOException {
        Objects.requireNonNull(clock, "clock");
        BufferedWriter writer = Files.newBufferedWriter(file, StandardCharsets.US_ASCII,
                StandardOpenOption.CREATE, StandardOpenOption.APPEND, StandardOpenOption.WRITE);
        return new WireLog(file, clock, writer);
    }

    /** @return the log file */
    public Path file() {
        return file;
    }

    /** Logs bytes that were sent. */
    void sent(byte[] data, int off, int len) {
        line('>', HEX.formatHex(data, off, off + len));
    }

    /** Logs bytes that were received. */
    void received(byte[] data, int off, int len) {
        line('<', HEX.formatHex(data, off, off + len));
    }

    /** Logs a note, such as a lost or restored link. */
    void note(String text) {
        line('#', text.replace('\n', ' '));
    }

    private synchronized void line(char direction, String text) {
        if (writer == null) {
            return;
        }
        try {
            writer.write(TIMESTAMP.format(clock.instant()) + ' ' + direction + ' ' + text);
            writer.write('\n');
            writer.flush();
        } catch (IOException e) {
            LOG.warn("wire log {} cannot be written, further lines are dropped: {}", file, e.getMessage());
            closeWriter();
        }
    }

    /** Closes the file. Idempotent. */
    @Override
    public synchronized void close() {
        closeWriter();
    }

    private void closeWriter() {
        if (writer == null) {
            return;
        }
        try {
            writer.close();
        } catch (IOException e) {
            LOG.warn("wire log {} did not close cleanly: {}", file, e.getMessage());
        }
        writer = null;
    }
}
