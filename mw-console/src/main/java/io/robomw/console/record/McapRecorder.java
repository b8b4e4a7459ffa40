package io.robomw.console.record;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.console.mcap.McapWriter;
import io.robomw.console.observe.Observation;
import io.robomw.console.observe.Observer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.BufferedOutputStream;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.HashMap;
import java.util.Map;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * Records observations into an MCAP file that Foxglove opens ({@link RecordingCodec} lists the
 * topics and schemas). Observations are queued and written by a thread of its own, so a source
 * (a world's stepping thread, a host watcher) never waits for the disk; if the disk cannot keep up
 * with {@value #QUEUE} queued observations, newer ones are dropped and counted (logged once, and
 * in the file's metadata). Every {@value #FLUSH_MILLIS} ms the open chunk is written out, so a
 * recorder killed with its process loses at most that much; {@link #close()} writes the summary
 * and the footer.
 */
public final class McapRecorder implements Observer, AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(McapRecorder.class);
    static final int QUEUE = 100_000;
    static final long FLUSH_MILLIS = 2_000;
    /** The recording format's version, in the file's "robomw" metadata. */
    public static final String FORMAT_VERSION = "1";
    private static final Observation STOP = new Observation.TopicMessage(0, "", "");

    private final Path file;
    private final McapWriter writer;
    private final BlockingQueue<Observation> queue = new ArrayBlockingQueue<>(QUEUE);
    private final Map<String, Integer> schemas = new HashMap<>();
    private final Map<String, Integer> channels = new HashMap<>();
    private final Map<Integer, Long> sequences = new HashMap<>();
    private final AtomicLong dropped = new AtomicLong();
    private final AtomicLong written = new AtomicLong();
    private final Thread thread;
    private final FailurePolicy failures;
    private volatile IOException failure;
    private volatile boolean closedWriter;

    private McapRecorder(Path file, Map<String, String> about, FailurePolicy failures) throws IOException {
        this.file = file;
        this.failures = failures;
        Path parent = file.toAbsolutePath().getParent();
        if (parent != null) {
            Files.createDirectories(parent);
        }
        this.writer = new McapWriter(new BufferedOutputStream(Files.newOutputStream(file), 1 << 16), McapWriter.Options.INDEXED);
        try {
            writer.start("", "robomw " + FORMAT_VERSION);
            Map<String, String> meta = new java.util.LinkedHashMap<>(about);
            meta.put("format", FORMAT_VERSION);
            writer.addMetadata("robomw", meta);
        } catch (IOException | RuntimeException e) {
            try {
                writer.abandon();
            } catch (IOException closing) {
                e.addSuppressed(closing);
            }
            throw e;
        }
        this.thread = new Thread(this::run, "console-recorder"); // run() catches whatever ends it, in one place
        thread.setDaemon(false);
        thread.start();
    }

    /**
     * Starts a recording.
     *
     * @param file  the .mcap file (replaced if it exists)
     * @param about what is recorded (command line, world...), kept as the file's "robomw" metadata
     * @return the recorder; close it to finish the file
     * @throws IOException if the file cannot be written (then it is closed again)
     */
    public static McapRecorder start(Path file, Map<String, String> about) throws IOException {
        return start(file, about, FailurePolicy.logging());
    }

    /**
     * Starts a recording.
     *
     * @param file     the .mcap file (replaced if it exists)
     * @param about    what is recorded, kept as the file's "robomw" metadata
     * @param failures where what ends the recording's thread goes
     * @return the recorder; close it to finish the file
     * @throws IOException if the file cannot be written (then it is closed again)
     */
    public static McapRecorder start(Path file, Map<String, String> about, FailurePolicy failures) throws IOException {
        return new McapRecorder(file, about, failures);
    }

    /** @return the file */
    public Path file() {
        return file;
    }

    /** @return messages written so far */
    public long written() {
        return written.get();
    }

    @Override
    public void observe(Observation o) {
        if (!queue.offer(o) && dropped.getAndIncrement() == 0) {
            LOG.warn("recording {}: the disk does not keep up; observations are being dropped (counted in the file)", file);
        }
    }

    private void run() {
        long lastFlush = System.nanoTime();
        try {
            while (true) {
                Observation o = queue.poll(FLUSH_MILLIS, TimeUnit.MILLISECONDS);
                if (o == STOP) {
                    return;
                }
                if (o != null) {
                    write(o);
                }
                if (System.nanoTime() - lastFlush > TimeUnit.MILLISECONDS.toNanos(FLUSH_MILLIS)) {
                    writer.flushChunk();
                    lastFlush = System.nanoTime();
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } catch (IOException e) {
            failure = e;
            LOG.error("recording {} failed; nothing more is recorded: {}", file, e.toString());
        } catch (Throwable e) {
            failure = new IOException(e.toString(), e);
            LOG.warn("recording {} failed; nothing more is recorded: {}", file, e.toString());
            failures.died(thread.getName(), e);
        }
    }

    private void write(Observation o) throws IOException {
        for (RecordingCodec.Out m : RecordingCodec.encode(o)) {
            int schema = schemas.computeIfAbsent(m.schema(), this::registerSchemaOf);
            int channel = channels.computeIfAbsent(m.topic(), t -> writer.registerChannel(schema, t, Schemas.MESSAGE_ENCODING, Map.of()));
            long seq = sequences.merge(channel, 1L, Long::sum) - 1;
            long t = Math.max(0, o.timeNanos());
            writer.addMessage(channel, seq & 0xFFFFFFFFL, t, t, m.json());
            written.incrementAndGet();
        }
    }

    private int registerSchemaOf(String name) {
        return writer.registerSchema(name, Schemas.SCHEMA_ENCODING, Schemas.json(name));
    }

    /**
     * Writes what is queued, the summary and the footer, and closes the file.
     *
     * @throws IOException if the file could not be written
     */
    @Override
    public void close() throws IOException {
        if (closedWriter) {
            return;
        }
        try {
            queue.put(STOP);
            thread.join(30_000);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        if (dropped.get() > 0) {
            writer.addMetadata("robomw-dropped", Map.of("observations", String.valueOf(dropped.get())));
        }
        writer.close();
        closedWriter = true;
        if (failure != null) {
            throw failure;
        }
        LOG.info("recording {} closed: {} messages{}", file, written.get(), dropped.get() > 0 ? ", " + dropped.get() + " observations dropped" : "");
    }
}
