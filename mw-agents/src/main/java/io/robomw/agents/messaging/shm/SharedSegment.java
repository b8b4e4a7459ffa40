package io.robomw.agents.messaging.shm;

import io.robomw.agents.messaging.spi.Publication;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.nio.MappedByteBuffer;
import java.nio.channels.FileChannel;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.nio.file.attribute.PosixFilePermissions;
import java.security.SecureRandom;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;
import java.util.concurrent.locks.ReentrantLock;

/**
 * A publisher's shared-memory segment: a file in {@code /dev/shm} readable and writable by this
 * user only (0600), mapped, holding a ring of records ({@link SegmentLayout}). A payload sent to
 * several subscribers is written once; each subscriber gets a {@link SharedReference} on its own
 * connection, in the connection's order, copies the payload out and writes the record's sequence
 * into its cell.
 *
 * <p><b>Room.</b> A record is reused once every attached subscriber that may hold it has copied it:
 * subscriber {@code i} with cell value {@code c} and last sequence sent {@code s} may hold record
 * {@code r} only if {@code c < r} and {@code c < s} (records reach each subscriber in increasing
 * sequence, because {@link #send} gives the sequence and queues the reference under one lock). A
 * publisher waits for room (parked, polling the cells) up to the send timeout; then the subscribers
 * that still hold the oldest record are told they lag ({@link Subscriber}'s callback closes their
 * connection: the same fate as a peer that does not read its TCP connection) and stop counting,
 * and the publisher goes on. A subscriber whose connection closes stops counting at once.
 *
 * <p><b>Why cells and not acknowledgement frames.</b> A cell costs the subscriber one release store
 * per payload and the publisher nothing until the ring is full; an acknowledgement frame would cost
 * a write and a read system call per payload per subscriber, about what the payload's TCP write
 * costs for 100 KB.
 *
 * <p>The file is unlinked by {@link #close}, or at the JVM's end if it was not closed (a shutdown
 * hook); a segment of a process that was killed ({@code kill -9}) is removed by the next segment
 * made on the host ({@link #removeStale}). Thread-safe.
 */
public final class SharedSegment implements AutoCloseable {

    /** How a reference frame is queued on one connection (in order with its other frames). */
    @FunctionalInterface
    public interface Queue {
        /**
         * @param referenceFrame the reference frame (shared by all subscribers of the payload; the queue copies it)
         * @throws IOException if the connection cannot take it
         */
        void send(byte[] referenceFrame) throws IOException;
    }

    private static final Logger LOG = LoggerFactory.getLogger(SharedSegment.class);
    /** Where segments go on Linux. */
    public static final Path DIRECTORY = Path.of("/dev/shm");
    private static final long FIRST_NAP_NANOS = 20_000;
    private static final long LONGEST_NAP_NANOS = 200_000;

    private final Path file;
    private final long nonce;
    private final int cells;
    private final int dataBytes;
    private final int dataOffset;
    private final String owner;
    private final MappedByteBuffer map;
    private final ReentrantLock lock = new ReentrantLock();
    /** The subscribers that count, under the lock. */
    private final List<Subscriber> attached = new ArrayList<>();
    private final Subscriber[] byCell;
    /** Records not yet known to be copied by all, oldest first, under the lock. */
    private final ArrayDeque<Record> live = new ArrayDeque<>();
    private int nextCell;
    /** Bytes of the ring handed out since it was made (a position; its remainder is the offset). */
    private long head;
    private long sequence;
    /** The record written last: the next subscriber of the same publication gets it too. */
    private Record newest;
    /** The publication in {@link #newest}, its frame or its {@link Publication} (only the newest is kept: a record in the ring needs no array). */
    private Object newestPublication;
    private volatile boolean closed;
    /** Unlinks the file if the JVM ends before {@link #close} (System.exit, SIGTERM); removed by close. */
    private final Thread unlinkAtExit;

    private record Record(long sequence, long start, long end, byte[] referenceFrame) {
    }

    /**
     * One subscriber connection's use of the segment: its cell, and whether it counts.
     * Made by {@link #attach}; counts from {@link #activate}; {@link #detach} when its connection closes.
     */
    public final class Subscriber {
        private final int cell;
        private final Runnable lagging;
        private boolean active;
        private boolean detached;
        /** The last sequence sent to it, under the segment's lock. */
        private long lastSent;

        private Subscriber(int cell, Runnable lagging) {
            this.cell = cell;
            this.lagging = lagging;
        }

        /** @return its cell */
        public int cell() {
            return cell;
        }

        /** The subscriber mapped the segment: references may go to it, and it counts from now. */
        public void activate() {
            lock.lock();
            try {
                if (!detached && !closed) {
                    active = true;
                    attached.add(this);
                }
            } finally {
                lock.unlock();
            }
        }

        /** Its connection closed: it stops counting and its cell is free. Idempotent. */
        public void detach() {
            lock.lock();
            try {
                if (!detached) {
                    detached = true;
                    active = false;
                    attached.remove(this);
                    byCell[cell] = null;
                }
            } finally {
                lock.unlock();
            }
        }

        /** @return whether references may go to it */
        public boolean active() {
            lock.lock();
            try {
                return active;
            } finally {
                lock.unlock();
            }
        }

        private long consumed() {
            return (long) SegmentLayout.LONG.getAcquire((ByteBuffer) map, SegmentLayout.cellOffset(cell));
        }

        /** @return whether it may still hold the record of {@code seq} */
        private boolean holds(long seq) {
            long c = consumed();
            return c < seq && c < lastSent;
        }

        @Override
        public String toString() {
            return "cell " + cell + " of " + file;
        }
    }

    private SharedSegment(Path file, long nonce, int cells, int dataBytes, MappedByteBuffer map) {
        this.file = file;
        this.nonce = nonce;
        this.cells = cells;
        this.dataBytes = dataBytes;
        this.dataOffset = SegmentLayout.controlBytes(cells);
        this.map = map;
        this.byCell = new Subscriber[cells];
        this.owner = file.getFileName().toString();
        this.unlinkAtExit = new Thread(() -> {
            try {
                Files.deleteIfExists(file);
            } catch (IOException e) {
                // the next segment made on this host removes it (its process has ended)
            }
        }, "robomw-shm-unlink-" + owner);
        Runtime.getRuntime().addShutdownHook(unlinkAtExit);
    }

    /**
     * Makes a segment: removes the segments of dead processes of this user, creates the file (0600),
     * writes all of it (so a full {@code /dev/shm} fails here, not later in a mapped write) and maps it.
     *
     * @param directory where ({@link #DIRECTORY})
     * @param dataBytes the ring's size, a multiple of 8
     * @param cells     how many subscribers may attach at once
     * @return the segment
     * @throws IOException if the file cannot be made or mapped
     */
    public static SharedSegment create(Path directory, int dataBytes, int cells) throws IOException {
        if (dataBytes % SegmentLayout.ALIGNMENT != 0 || dataBytes <= 0) {
            throw new IllegalArgumentException("a segment's ring must be a positive multiple of " + SegmentLayout.ALIGNMENT + " bytes, got " + dataBytes);
        }
        removeStale(directory);
        long nonce = new SecureRandom().nextLong();
        Path file = Files.createTempFile(directory, SegmentLayout.FILE_PREFIX + ProcessHandle.current().pid() + "-", ".seg",
                PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("rw-------")));
        try (FileChannel ch = FileChannel.open(file, StandardOpenOption.READ, StandardOpenOption.WRITE)) {
            int control = SegmentLayout.controlBytes(cells);
            long size = (long) control + dataBytes;
            ByteBuffer zeros = ByteBuffer.allocate(1 << 20);
            for (long at = 0; at < size; at += zeros.capacity()) {
                zeros.clear().limit((int) Math.min(zeros.capacity(), size - at));
                while (zeros.hasRemaining()) {
                    ch.write(zeros, at + zeros.position());
                }
            }
            MappedByteBuffer map = ch.map(FileChannel.MapMode.READ_WRITE, 0, size);
            map.order(ByteOrder.nativeOrder());
            map.putInt(SegmentLayout.VERSION_OFFSET, SegmentLayout.VERSION);
            map.putInt(SegmentLayout.CELL_COUNT_OFFSET, cells);
            map.putLong(SegmentLayout.NONCE_OFFSET, nonce);
            map.putInt(SegmentLayout.DATA_OFFSET_OFFSET, control);
            map.putInt(SegmentLayout.DATA_BYTES_OFFSET, dataBytes);
            SegmentLayout.LONG.setRelease((ByteBuffer) map, SegmentLayout.MAGIC_OFFSET, SegmentLayout.MAGIC);
            return new SharedSegment(file, nonce, cells, dataBytes, map);
        } catch (Throwable e) {
            // whatever stopped it (an Error too), the half-made file is not left in /dev/shm
            Files.deleteIfExists(file);
            throw e;
        }
    }

    /**
     * Removes the segment files in a directory whose process (the number in the name) has ended:
     * left by a publisher that was killed before it could unlink its segment. Files of other users
     * are left alone (the system refuses anyway).
     *
     * @param directory where
     * @return how many it removed
     */
    public static int removeStale(Path directory) {
        int removed = 0;
        try (var files = Files.newDirectoryStream(directory, SegmentLayout.FILE_PREFIX + "*")) {
            for (Path f : files) {
                String rest = f.getFileName().toString().substring(SegmentLayout.FILE_PREFIX.length());
                int dash = rest.indexOf('-');
                long pid;
                try {
                    pid = Long.parseLong(dash < 0 ? rest : rest.substring(0, dash));
                } catch (NumberFormatException e) {
                    continue;
                }
                if (ProcessHandle.of(pid).isEmpty()) {
                    try {
                        if (Files.deleteIfExists(f)) {
                            removed++;
                            LOG.info("removed the shared-memory segment {} of process {}, which has ended", f, pid);
                        }
                    } catch (IOException e) {
                        LOG.debug("cannot remove {}: {}", f, e.toString());
                    }
                }
            }
        } catch (IOException e) {
            LOG.debug("cannot list {}: {}", directory, e.toString());
        }
        return removed;
    }

    /** @return the file */
    public Path file() {
        return file;
    }

    /** @return the random number in its header */
    public long nonce() {
        return nonce;
    }

    /** @return the ring's size */
    public int dataBytes() {
        return dataBytes;
    }

    /**
     * Gives a subscriber connection a cell (not counted until {@link Subscriber#activate}).
     *
     * @param lagging run (on a publishing thread) when the subscriber held a record past the send
     *                timeout; it should close the subscriber's connection, which detaches it
     * @return the subscriber, or {@code null} if every cell is taken or the segment is closed
     */
    public Subscriber attach(Runnable lagging) {
        lock.lock();
        try {
            if (closed) {
                return null;
            }
            for (int i = 0; i < cells; i++) {
                // round robin: a cell freed last is reused last (its old owner's late write lands elsewhere)
                int c = (nextCell + i) % cells;
                if (byCell[c] == null) {
                    nextCell = c + 1;
                    Subscriber s = new Subscriber(c, lagging);
                    SegmentLayout.LONG.setRelease((ByteBuffer) map, SegmentLayout.cellOffset(c), 0L);
                    byCell[c] = s;
                    return s;
                }
            }
            return null;
        } finally {
            lock.unlock();
        }
    }

    /**
     * Sends a publication to one subscriber: writes its payload into the ring unless the record
     * written last holds this very publication (the same array: a publication goes to its
     * subscribers one after the other), then queues the reference frame on the subscriber's
     * connection, all under the segment's lock (so each connection's references increase).
     *
     * @param publication      an encoded PUBLISH frame without an HMAC, not changed after
     * @param to               an active subscriber
     * @param queue            its connection's queue
     * @param sendTimeoutNanos how long to wait for room before the laggards are closed
     * @throws IOException if the segment is closed, the payload cannot fit, or the wait was interrupted
     */
    public void send(byte[] publication, Subscriber to, Queue queue, long sendTimeoutNanos) throws IOException {
        int length = SharedReference.payloadLength(publication, 0);
        int headLength = publication.length - length;
        send(new Outgoing(publication, publication, headLength, publication, headLength, length), to, queue, sendTimeoutNanos);
    }

    /**
     * {@link #send(byte[], Subscriber, Queue, long)} of a publication that travels apart from its
     * frame: its payload is written into the ring from where it is, never copied into a frame.
     *
     * @param publication      a publication that {@link Publication#travelsApart() travels apart}
     * @param to               an active subscriber
     * @param queue            its connection's queue
     * @param sendTimeoutNanos how long to wait for room before the laggards are closed
     * @throws IOException as {@link #send(byte[], Subscriber, Queue, long)}
     */
    public void send(Publication publication, Subscriber to, Queue queue, long sendTimeoutNanos) throws IOException {
        byte[] head = publication.head();
        byte[] payload = publication.payload();
        send(new Outgoing(publication, head, head.length, payload, 0, payload.length), to, queue, sendTimeoutNanos);
    }

    /**
     * A publication on its way into the ring.
     *
     * @param key        what identifies it (the same object for each of its subscribers): its frame, or its {@link Publication}
     * @param head       an array starting with its head (header and names): its frame, or its {@link Publication#head()}
     * @param headLength the head's length
     * @param payload    an array holding its payload
     * @param payloadAt  where in {@code payload}
     * @param length     the payload's length
     */
    private record Outgoing(Object key, byte[] head, int headLength, byte[] payload, int payloadAt, int length) {
    }

    private void send(Outgoing out, Subscriber to, Queue queue, long sendTimeoutNanos) throws IOException {
        lock.lock();
        try {
            if (closed) {
                throw new IOException("shared-memory segment " + file + " is closed");
            }
            Record r = newest;
            if (r == null || newestPublication != out.key() || to.lastSent >= r.sequence) {
                r = write(out, sendTimeoutNanos);
            }
            queue.send(r.referenceFrame);
            to.lastSent = r.sequence;
        } finally {
            lock.unlock();
        }
    }

    /** Writes a publication's payload into a new record, waiting for room. Under the lock (let go while it naps). */
    private Record write(Outgoing out, long sendTimeoutNanos) throws IOException {
        int length = out.length();
        int bytes = SegmentLayout.recordBytes(length);
        if (bytes > dataBytes) {
            throw new IOException("a payload of " + length + " bytes does not fit the shared-memory ring of " + dataBytes + " bytes (" + file + ")");
        }
        long deadline = System.nanoTime() + sendTimeoutNanos;
        long nap = FIRST_NAP_NANOS;
        int at;
        int pad;
        while (true) {
            reclaim();
            // another publisher may have written while this one napped: where the record goes is worked out afresh
            at = (int) (head % dataBytes);
            pad = at + bytes > dataBytes ? dataBytes - at : 0;
            long tail = live.isEmpty() ? head : live.peekFirst().start();
            if (dataBytes - (head - tail) >= pad + bytes) {
                break;
            }
            if (closed) {
                throw new IOException("shared-memory segment " + file + " is closed");
            }
            if (System.nanoTime() - deadline >= 0) {
                closeLaggards(sendTimeoutNanos);
                deadline = System.nanoTime() + sendTimeoutNanos;
                continue;
            }
            lock.unlock();
            try {
                LockSupport.parkNanos(this, nap);
            } finally {
                lock.lock();
            }
            if (Thread.currentThread().isInterrupted()) {
                throw new IOException("interrupted while waiting for room in shared-memory segment " + file);
            }
            nap = Math.min(LONGEST_NAP_NANOS, nap * 2);
        }
        if (closed) {
            throw new IOException("shared-memory segment " + file + " is closed");
        }
        long start = head;
        int offset = (at + pad) % dataBytes;
        head += pad + bytes;
        long seq = ++sequence;
        int base = dataOffset + offset;
        map.put(base + SegmentLayout.RECORD_HEADER, out.payload(), out.payloadAt(), length);
        map.putInt(base + SegmentLayout.RECORD_LENGTH_OFFSET, length);
        SegmentLayout.LONG.setRelease((ByteBuffer) map, base, seq);
        Record r = new Record(seq, start, head, SharedReference.frameFor(out.head(), out.headLength(), length, seq, offset));
        live.addLast(r);
        newest = r;
        newestPublication = out.key();
        return r;
    }

    /** Forgets the oldest records every subscriber is done with. */
    private void reclaim() {
        while (!live.isEmpty()) {
            long seq = live.peekFirst().sequence();
            for (int i = 0; i < attached.size(); i++) {
                if (attached.get(i).holds(seq)) {
                    return;
                }
            }
            live.pollFirst();
        }
    }

    private void closeLaggards(long sendTimeoutNanos) {
        long seq = live.peekFirst().sequence();
        List<Subscriber> lagging = new ArrayList<>();
        for (Subscriber s : attached) {
            if (s.holds(seq)) {
                lagging.add(s);
            }
        }
        for (Subscriber s : lagging) {
            LOG.warn("shared-memory segment {}: the subscriber of {} has not copied record {} for {} ms; closing its connection",
                    owner, s, seq, TimeUnit.NANOSECONDS.toMillis(sendTimeoutNanos));
            s.detach();
            try {
                s.lagging.run();
            } catch (RuntimeException e) {
                LOG.warn("closing a lagging subscriber of {}: {}", owner, e.toString());
            }
        }
    }

    /** @return how many subscribers count now */
    public int attachedCount() {
        lock.lock();
        try {
            return attached.size();
        } finally {
            lock.unlock();
        }
    }

    /**
     * Unlinks the file; no more records are written (a publisher waiting for room fails). The
     * mapping goes with the last reference to this object. Idempotent.
     */
    @Override
    public void close() {
        closed = true;
        lock.lock();
        try {
            attached.clear();
            live.clear();
            newest = null;
            newestPublication = null;
        } finally {
            lock.unlock();
        }
        try {
            Files.deleteIfExists(file);
        } catch (IOException e) {
            LOG.warn("cannot remove shared-memory segment {}: {}", file, e.toString());
        }
        try {
            Runtime.getRuntime().removeShutdownHook(unlinkAtExit);
        } catch (IllegalStateException e) {
            // the JVM is ending: the hook runs, and finds the file gone
        }
    }

    @Override
    public String toString() {
        return "SharedSegment[" + file + "]";
    }
}
