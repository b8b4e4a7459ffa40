package io.robomw.agents.messaging.io;

import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;

import java.io.IOException;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.LockSupport;
import java.util.concurrent.locks.ReentrantLock;

/**
 * The frames waiting to go to one peer, in order, with the link's stream sequence numbers.
 *
 * <p>Senders {@link #send} frames; a writer thread ({@link #startWriter}) takes everything that
 * has gathered and writes it in one call (two more per large frame, see below), so a fast publisher's frames go out in large batches
 * (it sleeps up to 50 µs for a batch of publications to grow, see
 * {@link #linger}).
 * When nothing is waiting, a request or reply (any frame but a publication), or a publication
 * after {@value #IDLE_MICROS} µs of silence, is written at once on the sender's thread instead:
 * a request does not wait for the writer thread to wake up, and a stream of publications still
 * goes out in batches.
 * A stream faster than that is written by its senders: a sender that finds {@value #SENDER_BATCH_BYTES}
 * bytes or more waiting, and no batch being written, writes them itself, and the writer thread
 * leaves such a stream alone until it pauses (see {@link #writeFullBatch}). A sender blocked in such
 * a write, as in a direct one, is ended by its connection's {@link #stuck} check closing the link.
 * Transports without a writer thread (an RMI session, which the peer polls) {@link #take} the
 * batches themselves.
 *
 * <p>A frame of {@value #SHARED_FROM} bytes or more (a laser scan, a camera frame) is not copied
 * into the buffer: only its first {@value #HEAD} bytes are, with this link's sequence number, and
 * the writer writes the rest straight from the caller's array after them (a publication to eight
 * subscribers is encoded once and copied by none of them). The caller must not change such a frame
 * after {@link #send}.
 *
 * <p>At most {@code capacity} bytes wait; a sender waits for room up to the send timeout, then
 * gets an {@link IOException} (the caller closes the link: a peer that does not read must not
 * hold up the others).
 *
 * <p>Thread-safe. The writer thread is started once and ends when the buffer is closed.
 */
public final class OutboundBuffer {

    /** A link idle for this long gets its next frame written directly by the sender. */
    public static final long IDLE_MICROS = 20;

    /** Where batches go. */
    @FunctionalInterface
    public interface Writer {
        /**
         * @param buf    bytes
         * @param offset start
         * @param length count
         * @throws IOException if the peer is gone
         */
        void write(byte[] buf, int offset, int length) throws IOException;
    }

    /** Each of the two buffers starts this small and doubles as frames wait: an idle link holds 8 KiB. */
    private static final int INITIAL = 4 * 1024;
    /** Frames at least this large are written from the caller's array rather than copied into the buffer. */
    public static final int SHARED_FROM = 64 * 1024;
    /** The bytes of a shared frame copied into the buffer: its prefix and stream sequence number, which differ per link. */
    static final int HEAD = FrameCodec.STREAM_SEQUENCE_OFFSET + 8;

    /**
     * The rest of a large frame, from {@link #HEAD}, written from the caller's array after the
     * buffer's bytes up to {@code at}.
     *
     * @param at    where in the buffer the frame's head ends
     * @param frame the whole frame
     */
    private record Shared(int at, byte[] frame) {
    }

    /**
     * A batch taken to be written.
     *
     * @param bytes  the buffer holding it
     * @param length its bytes in {@code bytes}
     * @param shared its large frames, in order
     */
    private record Batch(byte[] bytes, int length, java.util.ArrayList<Shared> shared) {
    }
    private static final byte[] EMPTY = new byte[0];
    private static final int LINGER_BYTES = 32 * 1024;
    /** A sender writes the waiting batch itself once it is this large (see {@link #writeFullBatch}). */
    private static final int SENDER_BATCH_BYTES = 16 * 1024;
    private static final long LINGER_NANOS = 50_000;
    /** Naps of {@link #LINGER_NANOS} the writer takes on an empty buffer before it waits to be signalled (about 1 ms). */
    private static final int IDLE_POLLS = 16;

    private final ReentrantLock lock = new ReentrantLock();
    private final Condition hasData = lock.newCondition();
    private final Condition hasRoom = lock.newCondition();
    private final ReentrantLock writeLock = new ReentrantLock();
    private final int capacity;
    private final long sendTimeoutNanos;
    private final String peer;
    private byte[] fill = new byte[INITIAL];
    private byte[] spare = new byte[INITIAL];
    /** The large frames of {@code fill}, in order (under the lock). */
    private java.util.ArrayList<Shared> fillShared = new java.util.ArrayList<>(2);
    /** Those of {@code spare}: the batch being written. */
    private java.util.ArrayList<Shared> spareShared = new java.util.ArrayList<>(2);
    /** Bytes of large frames waiting beyond {@code used} (under the lock). */
    private int sharedBytes;
    /** Bytes waiting in {@code fill}: written under the lock with release stores (no fence per frame), read outside it with {@link #usedNow}. */
    private int used;
    private long sequence;
    private volatile long lastSendNanos = System.nanoTime() - TimeUnit.SECONDS.toNanos(1);
    private volatile boolean closed;
    private boolean writerWaiting;
    private boolean batchTaken;
    /** Batches senders have written, under the lock: the writer thread leaves a stream its senders write. */
    private long senderBatches;
    private Writer writer;
    private volatile Thread writerThread;
    private volatile long writingSinceNanos;
    private volatile boolean writing;
    private volatile boolean urgentWaiting;
    private volatile boolean lingering;

    /**
     * @param peer             the peer, for error messages
     * @param capacity         most bytes waiting
     * @param sendTimeoutNanos how long a sender waits for room
     */
    public OutboundBuffer(String peer, int capacity, long sendTimeoutNanos) {
        this.peer = peer;
        this.capacity = capacity;
        this.sendTimeoutNanos = sendTimeoutNanos;
    }

    /**
     * Starts the writer thread.
     *
     * @param out     where batches are written
     * @param threads makes the (one) writer thread
     * @param onError called on the writer thread if a write fails (the buffer is closed by then)
     */
    public void startWriter(Writer out, ThreadFactory threads, java.util.function.Consumer<IOException> onError) {
        lock.lock();
        try {
            if (writer != null) {
                throw new IllegalStateException("writer of " + peer + " already started");
            }
            writer = out;
        } finally {
            lock.unlock();
        }
        Thread t = threads.newThread(() -> {
            try {
                writeLoop(out);
            } catch (Throwable e) {
                // the link ends with its writer, whatever ended it; what is not an I/O failure also
                // ends the thread, which reports it (the threads' factory)
                close();
                lock.lock();
                try {
                    release();
                } finally {
                    lock.unlock();
                }
                onError.accept(e instanceof IOException io ? io : new IOException("the writer of " + peer + " failed: " + e, e));
                if (e instanceof RuntimeException r) {
                    throw r;
                }
                if (e instanceof Error err) {
                    throw err;
                }
            }
        });
        writerThread = t;
        t.start();
    }

    /**
     * Queues a frame (or writes it at once if the link is idle and has a writer).
     *
     * @param frame an encoded frame; copied (below {@value #SHARED_FROM} bytes; a larger one's head
     *              only, and it must not change after), and the copy gets this link's next stream sequence
     * @throws IOException if the buffer is closed, or stayed full for the send timeout
     */
    public void send(byte[] frame) throws IOException {
        boolean urgent = !publication(frame);
        // A publication joins frames already waiting without reading the clock: in a stream, that
        // is nearly every one (two clock reads were a tenth of a publication's cost).
        if (writer != null && (urgent || (usedNow() == 0 && System.nanoTime() - lastSendNanos > IDLE_MICROS * 1000)) && writeLock.tryLock()) {
            try {
                byte[] direct = null;
                boolean shared = frame.length >= SHARED_FROM;
                lock.lock();
                try {
                    long now = System.nanoTime();
                    if (!closed && used == 0 && !batchTaken && (urgent || now - lastSendNanos > IDLE_MICROS * 1000)) {
                        direct = shared ? java.util.Arrays.copyOf(frame, HEAD) : frame.clone();
                        FrameCodec.writeStreamSequence(direct, 0, ++sequence);
                    }
                    lastSendNanos = now;
                } finally {
                    lock.unlock();
                }
                if (direct != null) {
                    writeTimed(writer, direct, direct.length, shared ? java.util.List.of(new Shared(HEAD, frame)) : java.util.List.of());
                    return;
                }
            } finally {
                writeLock.unlock();
            }
        }
        append(frame);
        if (writer != null && usedNow() >= SENDER_BATCH_BYTES) {
            writeFullBatch();
        }
    }

    /**
     * Writes the waiting batch on the sender's thread once it has grown to {@value #SENDER_BATCH_BYTES}
     * bytes, unless a batch is being written: the buffer's bytes were just written by this thread, and
     * the writer thread on another processor would have to take them over (a stream of 64-byte
     * publications ran at 3.6-3.8 M a second when the scheduler put the writer there, 7-8 M when
     * beside the sender; docs/benchmarks.md, "Messaging").
     *
     * @throws IOException if the write fails (the caller closes the link)
     */
    private void writeFullBatch() throws IOException {
        if (!writeLock.tryLock()) {
            return;
        }
        try {
            Batch batch;
            lock.lock();
            try {
                if (closed || batchTaken || used < SENDER_BATCH_BYTES) {
                    return;
                }
                batch = takeBatch();
                senderBatches++;
            } finally {
                lock.unlock();
            }
            try {
                writeTimed(writer, batch);
            } finally {
                lock.lock();
                try {
                    batchWritten(batch);
                } finally {
                    lock.unlock();
                }
            }
        } finally {
            writeLock.unlock();
        }
    }

    /** Swaps the buffers and marks the batch taken (with the lock held): @return the batch */
    private Batch takeBatch() {
        Batch batch = new Batch(fill, used, fillShared);
        fill = spare;
        spare = batch.bytes();
        fillShared = spareShared;
        spareShared = batch.shared();
        sharedBytes = 0;
        setUsed(0);
        urgentWaiting = false;
        batchTaken = true;
        hasRoom.signalAll();
        return batch;
    }

    /**
     * Ends a batch's write, on whichever thread wrote it (with the lock held): the caller's large
     * frames are not kept beyond their write, the next batch may be taken, and a writer thread
     * waiting for this one to be written (see {@link #writeLoop}) looks again.
     */
    private void batchWritten(Batch batch) {
        batch.shared().clear();
        batchTaken = false;
        hasRoom.signalAll();
        if (writerWaiting) {
            writerWaiting = false;
            hasData.signal();
        }
    }

    /**
     * @return whether a frame is a publication (a {@code PUBLISH}, or a {@code PUBLISH_SHARED}
     *         reference to one in shared memory), which may wait a little to go out in a batch
     */
    private static boolean publication(byte[] frame) {
        byte kind = frame[FrameCodec.KIND_OFFSET];
        return kind == FrameKind.PUBLISH.code() || kind == FrameKind.PUBLISH_SHARED.code();
    }

    private void append(byte[] frame) throws IOException {
        int length = frame.length;
        lock.lock();
        try {
            long waitNanos = sendTimeoutNanos;
            while (!closed && used + sharedBytes + length > capacity && used > 0) {
                if (waitNanos <= 0) {
                    throw new IOException(peer + " took no frames for " + TimeUnit.NANOSECONDS.toMillis(sendTimeoutNanos)
                            + " ms with " + (used + sharedBytes) + " bytes waiting (limit " + capacity + "); it is not reading");
                }
                waitNanos = hasRoom.awaitNanos(waitNanos);
            }
            if (closed) {
                throw new IOException("link to " + peer + " is closed");
            }
            boolean shared = length >= SHARED_FROM;
            int copied = shared ? HEAD : length;
            if (used + copied > fill.length) {
                byte[] bigger = new byte[Math.max(used + copied, Math.min(capacity, fill.length * 2))];
                System.arraycopy(fill, 0, bigger, 0, used);
                fill = bigger;
            }
            if (used == 0) {
                // the first frame of a batch; the writer stamps the time again when it writes the batch
                lastSendNanos = System.nanoTime();
            }
            System.arraycopy(frame, 0, fill, used, copied);
            FrameCodec.writeStreamSequence(fill, used, ++sequence);
            if (shared) {
                fillShared.add(new Shared(used + HEAD, frame));
                sharedBytes += length - HEAD;
            }
            setUsed(used + copied);
            if (shared || !publication(frame)) {
                // a request or reply, or a frame large enough to be a batch alone: no lingering
                urgentWaiting = true;
                if (lingering) {
                    LockSupport.unpark(writerThread);
                }
            }
            if (writerWaiting) {
                // one signal per wake-up: the writer takes tens of microseconds to run, and a
                // publisher that signalled on every frame until then paid for it on each one
                writerWaiting = false;
                hasData.signal();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while waiting to send to " + peer, e);
        } finally {
            lock.unlock();
        }
    }

    /**
     * Queues a frame for the writer thread if nothing has been sent for {@code silentNanos} and
     * nothing waits or is being written; never blocks (a keep-alive from a housekeeping thread
     * must not wait for a peer that does not read).
     *
     * @param frame       an encoded frame (copied)
     * @param nowNanos    now
     * @param silentNanos how long the link must have been silent
     * @return whether it was queued
     */
    public boolean sendIfSilent(byte[] frame, long nowNanos, long silentNanos) {
        if (!lock.tryLock()) {
            return false;
        }
        try {
            if (closed || used > 0 || batchTaken || writing || nowNanos - lastSendNanos < silentNanos) {
                return false;
            }
            append(frame); // re-entrant; never waits: the buffer is empty and holds at least one frame
            return true;
        } catch (IOException e) {
            return false;
        } finally {
            lock.unlock();
        }
    }

    /**
     * Takes everything waiting, for a transport whose peer fetches frames (no writer thread).
     *
     * @param waitNanos how long to wait for something to arrive
     * @return the waiting frames, back to back; empty if none came in time or the buffer is closed
     * @throws InterruptedException if interrupted while waiting
     */
    public byte[] take(long waitNanos) throws InterruptedException {
        lock.lock();
        try {
            long left = waitNanos;
            while (used == 0 && !closed && left > 0) {
                writerWaiting = true;
                left = hasData.awaitNanos(left);
            }
            writerWaiting = false;
            byte[] out = merged();
            setUsed(0);
            if (closed) {
                release();
            }
            hasRoom.signalAll();
            return out;
        } finally {
            lock.unlock();
        }
    }

    /**
     * Stops accepting frames; the writer thread ends after what is waiting, and the buffers are
     * given back (a closed link may stay referenced for a while, by a request it sent that
     * waits for its reply: it must not keep its memory). Idempotent.
     */
    public void close() {
        lock.lock();
        try {
            closed = true;
            if (writer == null && used == 0) {
                release();
            }
            if (lingering) {
                LockSupport.unpark(writerThread);
            }
            hasData.signalAll();
            hasRoom.signalAll();
        } finally {
            lock.unlock();
        }
    }

    /**
     * Waits until the writer thread has written everything that was waiting (after {@link #close},
     * so a last reply is not lost when a link is closed on purpose). Returns at once on the writer
     * thread itself or without a writer.
     *
     * @param waitNanos the longest wait
     * @return whether everything was written
     */
    public boolean awaitDrained(long waitNanos) {
        if (writerThread == null || Thread.currentThread() == writerThread) {
            return false;
        }
        lock.lock();
        try {
            long left = waitNanos;
            while ((used > 0 || batchTaken) && left > 0 && writerThread.isAlive()) {
                left = hasRoom.awaitNanos(left);
            }
            return used == 0 && !batchTaken;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return false;
        } finally {
            lock.unlock();
        }
    }

    /** @return whether it is closed */
    public boolean isClosed() {
        lock.lock();
        try {
            return closed;
        } finally {
            lock.unlock();
        }
    }

    /**
     * @param nowNanos   now, from {@link System#nanoTime()}
     * @param limitNanos the send timeout
     * @return whether a write has been blocked for longer than the limit (the peer stopped reading)
     */
    public boolean stuck(long nowNanos, long limitNanos) {
        return writing && nowNanos - writingSinceNanos > limitNanos;
    }

    private static final java.lang.invoke.VarHandle USED;

    static {
        try {
            USED = java.lang.invoke.MethodHandles.lookup().findVarHandle(OutboundBuffer.class, "used", int.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    private void setUsed(int v) {
        USED.setRelease(this, v);
    }

    /** @return the bytes waiting, read without the lock (a hint: it may change at once) */
    private int usedNow() {
        return (int) USED.getOpaque(this);
    }

    /** @return the waiting bytes, large frames' rest included, back to back (with the lock held); clears the large frames */
    private byte[] merged() {
        if (fillShared.isEmpty()) {
            return java.util.Arrays.copyOf(fill, used);
        }
        byte[] out = new byte[used + sharedBytes];
        int from = 0;
        int to = 0;
        for (Shared s : fillShared) {
            System.arraycopy(fill, from, out, to, s.at() - from);
            to += s.at() - from;
            System.arraycopy(s.frame(), HEAD, out, to, s.frame().length - HEAD);
            to += s.frame().length - HEAD;
            from = s.at();
        }
        System.arraycopy(fill, from, out, to, used - from);
        fillShared.clear();
        sharedBytes = 0;
        return out;
    }

    /** Gives the buffers back once closed and empty (called with the lock held). */
    private void release() {
        fill = EMPTY;
        spare = EMPTY;
        fillShared.clear();
        spareShared.clear();
        sharedBytes = 0;
    }

    private void writeLoop(Writer out) throws IOException {
        int idlePolls = 0;
        while (true) {
            Batch batch;
            lockAsWriter();
            try {
                // a batch a sender is writing comes first, even once closed (it is not written yet)
                while ((used == 0 && !closed) || batchTaken) {
                    if (idlePolls > 0) {
                        // a stream of publications may only have paused: look again shortly rather
                        // than have the next sender pay for waking this thread up
                        idlePolls--;
                        lock.unlock();
                        try {
                            nap();
                        } finally {
                            lockAsWriter();
                        }
                        continue;
                    }
                    writerWaiting = true;
                    hasData.awaitUninterruptibly();
                }
                idlePolls = IDLE_POLLS;
                writerWaiting = false;
                if (used == 0) {
                    release();
                    return;
                }
                if (used + sharedBytes < LINGER_BYTES && !closed) {
                    long before = senderBatches;
                    lock.unlock();
                    try {
                        linger();
                    } finally {
                        lockAsWriter();
                    }
                    if ((senderBatches != before && !urgentWaiting && !closed) || batchTaken || used == 0) {
                        // its senders are writing this stream (or one is writing now): look again later
                        continue;
                    }
                }
                batch = takeBatch();
            } finally {
                lock.unlock();
            }
            writeLock.lock();
            try {
                writeTimed(out, batch);
            } finally {
                lockAsWriter();
                batchWritten(batch);
                lock.unlock();
                writeLock.unlock();
            }
        }
    }

    /**
     * Takes the lock for the writer thread, spinning briefly while a sender holds it (a sender
     * holds it for one copy) instead of queueing at once: a writer queued on the lock makes every
     * sender's unlock hand it a wake-up, which cost the publisher a sixth of its time.
     */
    private void lockAsWriter() {
        for (int i = 0; i < 200; i++) {
            if (lock.tryLock()) {
                return;
            }
            Thread.onSpinWait();
        }
        lock.lock();
    }

    /**
     * Lets a burst of publications gather for up to 50 µs before writing it,
     * asleep meanwhile: fewer, larger writes (and fewer wake-ups of the reader at the other end)
     * when publications come faster than the link takes single frames, and the processor left to
     * the publisher and the reader. Ends at once for a request or reply. A lone publication does
     * not come this way when the link is idle (see {@link #send}). (Gathering by yielding until
     * the buffer stopped growing, as before, made batches of a few frames whenever the publisher
     * was a little slower than the writer, and every batch cost the publisher a wake-up signal:
     * publish/subscribe throughput then fell to a third.)
     */
    /** Sleeps {@value #LINGER_NANOS} ns, or until closed or a request or reply comes. */
    private void nap() {
        lingering = true;
        try {
            if (!urgentWaiting && !closed) {
                LockSupport.parkNanos(LINGER_NANOS);
            }
        } finally {
            lingering = false;
        }
    }

    private void linger() {
        long until = System.nanoTime() + LINGER_NANOS;
        long left;
        lingering = true;
        try {
            while (usedNow() < LINGER_BYTES && !urgentWaiting && !closed && (left = until - System.nanoTime()) > 0) {
                LockSupport.parkNanos(left);
            }
        } finally {
            lingering = false;
        }
    }

    /** Writes a batch taken from the buffers. */
    private void writeTimed(Writer out, Batch batch) throws IOException {
        writeTimed(out, batch.bytes(), batch.length(), batch.shared());
    }

    /** Writes {@code buf}'s first {@code length} bytes, each large frame's rest after its head. */
    private void writeTimed(Writer out, byte[] buf, int length, java.util.List<Shared> shared) throws IOException {
        long now = System.nanoTime();
        writingSinceNanos = now;
        lastSendNanos = now;
        writing = true;
        try {
            int from = 0;
            for (int i = 0; i < shared.size(); i++) {
                Shared s = shared.get(i);
                out.write(buf, from, s.at() - from);
                out.write(s.frame(), HEAD, s.frame().length - HEAD);
                from = s.at();
            }
            if (length > from) {
                out.write(buf, from, length - from);
            }
        } finally {
            writing = false;
        }
    }
}
