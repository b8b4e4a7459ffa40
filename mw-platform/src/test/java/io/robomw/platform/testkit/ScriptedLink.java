package io.robomw.platform.testkit;

import io.robomw.api.Clock;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InterruptedIOException;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Comparator;
import java.util.Deque;
import java.util.Iterator;
import java.util.List;
import java.util.Objects;
import java.util.PriorityQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;
import java.util.function.Function;
import java.util.function.Supplier;

/**
 * The tests' one fake {@link Link}: the far end (a brick, an IR tower, a driver writing to an
 * emulator) is played by the test. It keeps what is written, delivers what the test scripts or
 * what a responder answers, and can lose the link, fail a transfer, block reads or be unplugged.
 *
 * <pre>{@code
 * ScriptedLink link = new ScriptedLink().named("slow echo")
 *         .answeringWith(written -> Answer.of(written).after(Duration.ofMillis(600)));
 * ScriptedLink nxt = new ScriptedLink().framedBy(Framing.lengthPrefixed16LittleEndian())
 *         .answering(telegram -> reply(telegram));
 * ScriptedLink script = new ScriptedLink().deliver(head).deliver(tail).deliverLoss();
 * }</pre>
 *
 * <h2>What arrives</h2>
 * Bytes arrive in pieces, and a read returns at most one piece, or the start of it if it asks for
 * fewer bytes (the rest stays for the next read), so a test decides exactly how the stream is
 * split. Pieces come from the test ({@link #deliver}, {@link #deliverLoss}, {@link #deliverFailure}),
 * or from the responder, which answers each write, or each frame of the writes if a
 * {@link Framing} is set ({@link #answering}, {@link #answeringWith}); an {@link Answer} may arrive
 * later on the link's clock ({@link #clockedBy}, the wall clock unless set) or once a latch is
 * released. Pieces arrive in the order they are due, those due together in the order they were
 * made. Empty pieces are not delivered.
 *
 * <h2>Reads</h2>
 * A read waits up to its timeout (wall-clock time, as {@link Link#read} says) for a piece to
 * arrive, as a real link does; {@link #timingOutAtOnce()} makes one that nothing will reach in
 * time return 0 at once. {@link #blockReads()} makes reads wait, whatever their timeout, until
 * {@link #releaseReads()}, a close or an unplug.
 *
 * <h2>Life cycle</h2>
 * Created closed, as a link is; transfers on a closed link throw an {@link IOException} naming it,
 * and a close ends a read waiting on another thread the same way. What is on its way survives a
 * close and an open, as a serial port's input does. {@link #unplug()} takes the far end away: what
 * was on its way is lost, transfers on the open link throw {@link LinkLostException} until it is
 * closed and opened again, and opening fails until {@link #plugIn()}.
 *
 * <h2>Threads</h2>
 * Thread-safe: one thread may read while another writes and the test delivers or unplugs from a
 * third. Responders run on the writing thread, holding the link's lock, and must not block; the
 * hook {@link #afterReadingEachPiece} runs on the reading thread, without it.
 */
public final class ScriptedLink implements Link {

    /** The longest a read waits before it looks at the clock and the latches again. */
    private static final long LOOK_AGAIN_NANOS = TimeUnit.MILLISECONDS.toNanos(1);
    /** A blocked read fails the test after this long, rather than hang the build. */
    private static final Duration BLOCKED_AT_MOST = Duration.ofSeconds(60);
    private static final Duration CENTURY = Duration.ofDays(36_525);

    /**
     * A piece on its way or arrived, or a failure waiting for the read that reaches it ({@code null}
     * for a scripted loss, which is made when it is read, so that it names the link as it is then).
     */
    private static final class Part {
        final byte[] bytes;
        final Throwable failure;
        final long due;
        final long sequence;
        final CountDownLatch hold;
        int consumed;

        Part(byte[] bytes, Throwable failure, long due, long sequence, CountDownLatch hold) {
            this.bytes = bytes;
            this.failure = failure;
            this.due = due;
            this.sequence = sequence;
            this.hold = hold;
        }
    }

    private final ReentrantLock lock = new ReentrantLock();
    private final Condition changed = lock.newCondition();

    private volatile String name = "scripted";
    private Clock clock = Clock.system();
    private Function<byte[], Answer> responder = written -> Answer.none();
    private Framing framing;
    private boolean timingOutAtOnce;
    private Runnable afterPiece = () -> { };

    private final PriorityQueue<Part> onTheWay = new PriorityQueue<>(
            Comparator.<Part>comparingLong(p -> p.due).thenComparingLong(p -> p.sequence));
    private final List<Part> held = new ArrayList<>();
    private final Deque<Part> arrived = new ArrayDeque<>();
    private final ByteArrayOutputStream unframed = new ByteArrayOutputStream();
    private final Deque<Throwable> writeFailures = new ArrayDeque<>();
    private long sequence;

    private boolean open;
    private boolean lost;
    private boolean unplugged;
    private boolean readsBlocked;
    private int blockedReads;

    private int reads;
    private int opens;
    private int closes;
    private final List<byte[]> writes = new ArrayList<>();
    private final List<Long> writeTimes = new ArrayList<>();
    private int taken;

    // ---- set-up (fluent)

    /**
     * @param describe what {@link #describe()} returns, for messages, logs and thread names
     * @return this link
     */
    public ScriptedLink named(String describe) {
        return locked(() -> name = Objects.requireNonNull(describe, "describe"));
    }

    /**
     * @param clock the clock answers' delays and due times are measured on, and writes are
     *              stamped with; a {@link io.robomw.api.ManualClock} makes them wait until the test
     *              advances it (a waiting read looks at it every millisecond)
     * @return this link
     */
    public ScriptedLink clockedBy(Clock clock) {
        return locked(() -> this.clock = Objects.requireNonNull(clock, "clock"));
    }

    /**
     * @param reply from the bytes of a write (or of a frame, see {@link #framedBy}) to the bytes
     *              the far end sends back at once, as one piece; {@code null} or empty for none
     * @return this link
     */
    public ScriptedLink answering(Function<byte[], byte[]> reply) {
        Objects.requireNonNull(reply, "reply");
        return answeringWith(written -> {
            byte[] bytes = reply.apply(written);
            return bytes == null ? Answer.none() : Answer.of(bytes);
        });
    }

    /**
     * @param responder from the bytes of a write (or of a frame, see {@link #framedBy}) to what
     *                  the far end sends back, and when
     * @return this link
     */
    public ScriptedLink answeringWith(Function<byte[], Answer> responder) {
        return locked(() -> this.responder = Objects.requireNonNull(responder, "responder"));
    }

    /**
     * @param framing how the far end cuts what is written into frames; the responder then answers
     *                each whole frame instead of each write
     * @return this link
     */
    public ScriptedLink framedBy(Framing framing) {
        return locked(() -> this.framing = Objects.requireNonNull(framing, "framing"));
    }

    /**
     * Makes a read return 0 at once when no piece has arrived and none is due on the clock within
     * its timeout (a piece held by a latch is not), instead of waiting its timeout out: a fuzz
     * test's thousands of silent bricks then take no time. Only for a test that has no other
     * thread delivering.
     *
     * @return this link
     */
    public ScriptedLink timingOutAtOnce() {
        return locked(() -> timingOutAtOnce = true);
    }

    /**
     * @param hook what happens on the reading thread each time a read has taken the last byte of
     *             a piece, before the read returns (a host that loses the processor after reading
     *             an answer parks here)
     * @return this link
     */
    public ScriptedLink afterReadingEachPiece(Runnable hook) {
        return locked(() -> afterPiece = Objects.requireNonNull(hook, "hook"));
    }

    // ---- the far end

    /**
     * @param piece bytes that arrive now, as one piece
     * @return this link
     */
    public ScriptedLink deliver(byte[] piece) {
        return locked(() -> {
            if (piece.length > 0) {
                schedule(piece.clone(), null, clock.nanoTime(), null);
            }
        });
    }

    /**
     * Makes the read that reaches this point of what arrives throw {@link LinkLostException}, as a
     * link whose peer hung up does; the link stays open and goes on with what arrives after.
     *
     * @return this link
     */
    public ScriptedLink deliverLoss() {
        return locked(() -> schedule(null, null, clock.nanoTime(), null));
    }

    /**
     * @param failure what the read that reaches this point of what arrives throws: an
     *                {@link IOException}, a {@link RuntimeException} or an {@link Error}
     * @return this link
     */
    public ScriptedLink deliverFailure(Throwable failure) {
        requireThrowable(failure);
        return locked(() -> schedule(null, failure, clock.nanoTime(), null));
    }

    /**
     * @param failure what the next write throws instead of taking its bytes: an
     *                {@link IOException}, a {@link RuntimeException} or an {@link Error}
     * @return this link
     */
    public ScriptedLink failNextWrite(Throwable failure) {
        requireThrowable(failure);
        return locked(() -> writeFailures.add(failure));
    }

    /**
     * Takes the far end away (a brick out of Bluetooth range, a USB adapter pulled): what was on
     * its way is lost, transfers on the open link throw {@link LinkLostException}, and
     * {@link #open()} fails until {@link #plugIn()}.
     */
    public void unplug() {
        locked(() -> {
            unplugged = true;
            lost = true;
            onTheWay.clear();
            held.clear();
            arrived.clear();
            unframed.reset();
        });
    }

    /** Brings the far end back: the link can be opened again (an open link stays lost until then). */
    public void plugIn() {
        locked(() -> unplugged = false);
    }

    /** Makes reads wait, whatever their timeout, until {@link #releaseReads()}, a close or an unplug. */
    public void blockReads() {
        locked(() -> readsBlocked = true);
    }

    /** Lets blocked reads go on. */
    public void releaseReads() {
        locked(() -> readsBlocked = false);
    }

    // ---- what happened

    /** @return how many reads were made, including those that returned nothing or threw */
    public int reads() {
        return get(() -> reads);
    }

    /** @return how many reads wait in {@link #blockReads()} now */
    public int blockedReads() {
        return get(() -> blockedReads);
    }

    /** @return how many writes the link took (a write that threw is not one) */
    public int writes() {
        return get(writes::size);
    }

    /** @return the bytes of every write taken, in order */
    public List<byte[]> eachWrite() {
        return get(() -> writes.stream().map(byte[]::clone).toList());
    }

    /** @return when each write taken was made, on the link's clock */
    public List<Long> writeTimes() {
        return get(() -> List.copyOf(writeTimes));
    }

    /** @return every byte written, in order */
    public byte[] written() {
        return get(() -> concat(writes));
    }

    /** @return the bytes written since the last call (or since the link was made) */
    public byte[] takeWritten() {
        return get(() -> {
            byte[] out = concat(writes.subList(taken, writes.size()));
            taken = writes.size();
            return out;
        });
    }

    /** @return how many times the link was opened (an open link's open does not count) */
    public int opens() {
        return get(() -> opens);
    }

    /** @return how many times the open link was closed */
    public int closes() {
        return get(() -> closes);
    }

    // ---- Link

    /**
     * Opens the link; one that was lost is usable again.
     *
     * @throws IOException naming the link, if the far end is unplugged
     */
    @Override
    public void open() throws IOException {
        lock.lock();
        try {
            if (unplugged) {
                throw new IOException(name + ": cannot open: no such device (the far end is unplugged)");
            }
            if (!open) {
                open = true;
                lost = false;
                opens++;
            }
            changed.signalAll();
        } finally {
            lock.unlock();
        }
    }

    @Override
    public boolean isOpen() {
        return get(() -> open);
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        Objects.checkFromIndexSize(off, len, data.length);
        lock.lock();
        try {
            requireUsable();
            Throwable failure = writeFailures.poll();
            if (failure != null) {
                throw rethrown(failure);
            }
            byte[] bytes = Arrays.copyOfRange(data, off, off + len);
            long now = clock.nanoTime();
            writes.add(bytes);
            writeTimes.add(now);
            for (byte[] frame : frames(bytes)) {
                Answer answer = Objects.requireNonNull(responder.apply(frame.clone()),
                        () -> name + ": the responder answered null to " + Arrays.toString(frame) + ": answer Answer.none() for silence");
                for (Answer.Piece p : answer.pieces()) {
                    long due = p.timing() == Answer.Timing.AT ? p.nanos() : now + p.nanos();
                    schedule(p.bytes(), null, due, p.hold());
                }
            }
            changed.signalAll();
        } finally {
            lock.unlock();
        }
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Objects.checkFromIndexSize(off, len, buf.length);
        Runnable pieceDone = null;
        int n;
        lock.lock();
        try {
            reads++;
            long deadline = System.nanoTime() + nanos(timeout);
            while (true) {
                requireUsable();
                if (len == 0) {
                    return 0;
                }
                if (readsBlocked) {
                    waitWhileBlocked();
                    continue;
                }
                arrive();
                Part head = arrived.peekFirst();
                if (head != null) {
                    if (head.bytes == null) {
                        arrived.pollFirst();
                        throw head.failure == null ? new LinkLostException(name, "scripted loss") : rethrown(head.failure);
                    }
                    n = Math.min(len, head.bytes.length - head.consumed);
                    System.arraycopy(head.bytes, head.consumed, buf, off, n);
                    head.consumed += n;
                    if (head.consumed == head.bytes.length) {
                        arrived.pollFirst();
                        pieceDone = afterPiece;
                    }
                    break;
                }
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    return 0;
                }
                long wait = left;
                if (!onTheWay.isEmpty()) {
                    long dueIn = onTheWay.peek().due - clock.nanoTime();
                    if (timingOutAtOnce && dueIn > left && held.isEmpty()) {
                        return 0;
                    }
                    wait = Math.min(wait, Math.min(Math.max(dueIn, 1), LOOK_AGAIN_NANOS));
                } else if (!held.isEmpty()) {
                    wait = Math.min(wait, LOOK_AGAIN_NANOS);
                } else if (timingOutAtOnce) {
                    return 0;
                }
                awaitNanos(wait);
            }
        } finally {
            lock.unlock();
        }
        if (pieceDone != null) {
            pieceDone.run();
        }
        return n;
    }

    @Override
    public String describe() {
        return name;
    }

    /** Closes the link; a read or write waiting on another thread throws. Idempotent. */
    @Override
    public void close() {
        locked(() -> {
            if (open) {
                open = false;
                closes++;
            }
        });
    }

    @Override
    public String toString() {
        return "ScriptedLink[" + describe() + "]";
    }

    // ---- inside (the lock held)

    private void requireUsable() throws IOException {
        if (!open) {
            throw new IOException(name + " is closed");
        }
        if (lost) {
            throw new LinkLostException(name, "the far end was unplugged");
        }
    }

    private void schedule(byte[] bytes, Throwable failure, long due, CountDownLatch hold) {
        Part part = new Part(bytes, failure, due, sequence++, hold);
        if (hold != null) {
            held.add(part);
        } else {
            onTheWay.add(part);
        }
        changed.signalAll();
    }

    /** Moves what has been released and is due to the pieces that arrived, in the order they are due. */
    private void arrive() {
        for (Iterator<Part> it = held.iterator(); it.hasNext(); ) {
            Part p = it.next();
            if (p.hold.getCount() == 0) {
                it.remove();
                onTheWay.add(p);
            }
        }
        long now = clock.nanoTime();
        while (!onTheWay.isEmpty() && onTheWay.peek().due - now <= 0) {
            arrived.add(onTheWay.poll());
        }
    }

    /** @return the whole frames the bytes complete, keeping the start of the next one */
    private List<byte[]> frames(byte[] bytes) {
        if (framing == null) {
            return List.of(bytes);
        }
        unframed.writeBytes(bytes);
        byte[] all = unframed.toByteArray();
        List<byte[]> out = new ArrayList<>();
        int at = 0;
        while (at < all.length) {
            int length = framing.frameLength(all, at, all.length - at);
            if (length < 0) {
                throw new IllegalStateException(name + ": the framing gave a frame of " + length + " bytes at byte " + at);
            }
            if (length == 0 || length > all.length - at) {
                break;
            }
            out.add(Arrays.copyOfRange(all, at, at + length));
            at += length;
        }
        unframed.reset();
        unframed.write(all, at, all.length - at);
        return out;
    }

    private void waitWhileBlocked() throws IOException {
        long deadline = System.nanoTime() + BLOCKED_AT_MOST.toNanos();
        blockedReads++;
        changed.signalAll();
        try {
            while (readsBlocked && open && !lost) {
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    throw new AssertionError(name + ": a read was blocked for " + BLOCKED_AT_MOST.toSeconds()
                            + " s: the test never called releaseReads()");
                }
                awaitNanos(left);
            }
        } finally {
            blockedReads--;
        }
    }

    private void awaitNanos(long nanos) throws InterruptedIOException {
        try {
            changed.awaitNanos(nanos);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            InterruptedIOException io = new InterruptedIOException(name + ": interrupted while reading");
            io.initCause(e);
            throw io;
        }
    }

    /** @return the timeout in nanoseconds, 0 if negative, a century if longer */
    private static long nanos(Duration timeout) {
        return timeout.isNegative() ? 0 : timeout.compareTo(CENTURY) > 0 ? CENTURY.toNanos() : timeout.toNanos();
    }

    private static byte[] concat(List<byte[]> parts) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        parts.forEach(out::writeBytes);
        return out.toByteArray();
    }

    private static void requireThrowable(Throwable failure) {
        if (!(failure instanceof IOException || failure instanceof RuntimeException || failure instanceof Error)) {
            throw new IllegalArgumentException("a link throws an IOException, a RuntimeException or an Error, not " + failure);
        }
    }

    /** @return the IOException to throw; throws the unchecked ones itself */
    private static IOException rethrown(Throwable failure) {
        if (failure instanceof RuntimeException e) {
            throw e;
        }
        if (failure instanceof Error e) {
            throw e;
        }
        return (IOException) failure;
    }

    // ---- locking

    private ScriptedLink locked(Runnable action) {
        lock.lock();
        try {
            action.run();
            changed.signalAll();
        } finally {
            lock.unlock();
        }
        return this;
    }

    private <T> T get(Supplier<T> query) {
        lock.lock();
        try {
            return query.get();
        } finally {
            lock.unlock();
        }
    }
}
