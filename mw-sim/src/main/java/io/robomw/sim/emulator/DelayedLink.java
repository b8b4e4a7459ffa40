package io.robomw.sim.emulator;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.Arrays;
import java.util.Deque;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.LockSupport;
import java.util.concurrent.locks.ReentrantLock;

/**
 * An emulator's end of a link, slowed down to a {@link LinkModel}: a delay line each way over
 * the real link (a pseudo-terminal or a TCP server). Each direction is one wire: what is handed to
 * it at a moment starts when the wire is free, each byte then takes {@code bitsPerByte / baud},
 * and the latency is added; latencies overlap, so a batch written back to back arrives back to
 * back. Bytes reach the emulator one by one as each arrives, so a telegram's arrival
 * ({@link #lastDeliveredAt()}) is when its own last byte arrived, even when the driver wrote
 * several at once.
 *
 * <p>With latency, a pump thread reads what the driver writes off the real link at once and
 * stamps it, and a sender thread puts the emulator's replies on the real link when they would
 * arrive, so replies' latencies overlap as the telegrams' do. Without latency (a plain serial
 * line) neither is needed: the emulator's thread stamps what it reads and waits out the bytes'
 * time itself, so a loaded host holds up one thread, not three. Time is the wall clock: a link's
 * delay is physical time, as a brick's is.
 *
 * <p>A peer that leaves (a TCP client) reaches the emulator as the {@link LinkLostException} it
 * would have got from the real link, after the bytes that came before it; replies still queued
 * for that peer are dropped, and the pump goes on reading, which accepts the next peer.
 *
 * <p>Threads: one thread may read while another writes, as {@link Link} allows; the pump and
 * sender threads ({@code <link>-in}, {@code <link>-out}, {@link OwnerThread}s) end on
 * {@link #close()}. They hand what they catch to the {@link FailurePolicy}: a survivable failure of
 * one read or one write is reported and the thread goes on; one nothing survives ends it cleanly,
 * and closes the link, so its reader gets an error naming the failure instead of silence.
 */
final class DelayedLink implements Link {

    private static final Logger LOG = LoggerFactory.getLogger(DelayedLink.class);
    private static final Duration PUMP_POLL = Duration.ofMillis(50);
    private static final int CHUNK_BYTES = 4096;

    private final Link inner;
    private final LinkModel model;
    private final boolean inline;
    private final long byteNanos;
    private final ReentrantLock lock = new ReentrantLock();
    private final Condition inboundChanged = lock.newCondition();
    private final Condition outboundChanged = lock.newCondition();
    private final Deque<Chunk> inbound = new ArrayDeque<>();
    private final Deque<Chunk> outbound = new ArrayDeque<>();
    private final OwnerThread pump;
    private final OwnerThread sender;
    private final byte[] inlineBuffer = new byte[CHUNK_BYTES];
    private long inboundWireFree;
    private long outboundWireFree;
    private volatile long lastDeliveredAt = System.nanoTime();
    /** When the last bytes read from the real link were put on the modelled one. */
    private volatile long lastInboundAt;
    private volatile boolean closed;
    /** What killed the pump or the sender, once one died. */
    private volatile Throwable death;

    /**
     * Bytes whose first starts arriving at {@code startAt}, each taking {@code byteNanos}, or (with
     * {@code lost} set) the news that the peer left.
     */
    private static final class Chunk {
        final byte[] bytes;
        final long startAt;
        final LinkLostException lost;
        int consumed;

        Chunk(byte[] bytes, long startAt, LinkLostException lost) {
            this.bytes = bytes;
            this.startAt = startAt;
            this.lost = lost;
        }
    }

    /**
     * Starts the pump and sender threads over an open link, if the model has latency.
     *
     * @param inner    the real link, open
     * @param model    how slow to make it
     * @param failures where the pump and the sender report what they catch
     */
    DelayedLink(Link inner, LinkModel model, FailurePolicy failures) {
        this.inner = inner;
        this.model = model;
        this.byteNanos = model.transmissionNanos(1);
        this.inline = model.latency().isZero();
        if (inline) {
            this.pump = null;
            this.sender = null;
            return;
        }
        Pump in = new Pump();
        Sender out = new Sender();
        this.pump = OwnerThread.start(inner.describe() + "-in", Thread.NORM_PRIORITY, in, EmulatorThreads.BACK_OFF, failures);
        in.self = pump;
        this.sender = OwnerThread.start(inner.describe() + "-out", Thread.NORM_PRIORITY, out, EmulatorThreads.BACK_OFF, failures);
        out.self = sender;
    }

    /** @return when byte {@code index} of a chunk has arrived */
    private long dueAt(Chunk c, int index) {
        return c.startAt + (index + 1) * byteNanos;
    }

    /** A chunk handed to a wire now: it starts when the wire is free, after the latency. */
    private Chunk onWire(byte[] bytes, boolean in) {
        long now = System.nanoTime();
        long free = in ? inboundWireFree : outboundWireFree;
        long start = Math.max(now, free);
        long end = start + bytes.length * byteNanos;
        if (in) {
            lastInboundAt = now;
            inboundWireFree = end;
        } else {
            outboundWireFree = end;
        }
        return new Chunk(bytes, start + model.latency().toNanos(), null);
    }

    /**
     * Ends the loop of the thread running a duty once the link is closed (by {@link #close()}, or
     * because the other thread died), from that thread itself.
     *
     * @return whether the link is closed
     */
    private boolean endedWithTheLink(OwnerThread self) {
        if (!closed) {
            return false;
        }
        if (self != null) { // null only in the moment before start() returned it
            self.close();
        }
        return true;
    }

    /** Reads what the driver writes off the real link at once, and stamps it. */
    private final class Pump implements OwnerThread.Duty {
        private final byte[] buf = new byte[CHUNK_BYTES];
        private volatile OwnerThread self;

        /** @return 1: bytes were read, the peer left, or the poll interval passed; 0 once the link is closed */
        @Override
        public int doWork() throws IOException {
            if (endedWithTheLink(self)) {
                return 0;
            }
            try {
                int n = inner.read(buf, 0, buf.length, PUMP_POLL);
                if (n > 0) {
                    lock.lock();
                    try {
                        inbound.add(onWire(Arrays.copyOf(buf, n), true));
                        inboundChanged.signalAll();
                    } finally {
                        lock.unlock();
                    }
                }
            } catch (LinkLostException e) {
                lock.lock();
                try {
                    inbound.add(new Chunk(new byte[0], System.nanoTime(), e));
                    outbound.clear();
                    inboundChanged.signalAll();
                } finally {
                    lock.unlock();
                }
            } catch (IOException e) {
                if (closed) {
                    return 0;
                }
                throw e;
            }
            return 1;
        }

        @Override
        public void onDeath(Throwable failure) {
            died(failure);
        }
    }

    /** Puts the emulator's replies on the real link when they would arrive. */
    private final class Sender implements OwnerThread.Duty {

        /** The longest the sender waits for a reply to send before it looks at whether the link closed. */
        private static final long IDLE_WAIT_NANOS = PUMP_POLL.toNanos();
        private volatile OwnerThread self;

        /** @return 1: a reply was sent, or one was waited for; 0 once the link is closed */
        @Override
        public int doWork() throws IOException, InterruptedException {
            if (endedWithTheLink(self)) {
                return 0;
            }
            Chunk next;
            lock.lock();
            try {
                next = outbound.peekFirst();
                long wait = next == null ? IDLE_WAIT_NANOS : dueAt(next, next.bytes.length - 1) - System.nanoTime();
                if (next == null || wait > 0) {
                    outboundChanged.awaitNanos(Math.min(wait, IDLE_WAIT_NANOS));
                    return 1;
                }
                outbound.pollFirst();
            } finally {
                lock.unlock();
            }
            try {
                inner.write(next.bytes, 0, next.bytes.length);
            } catch (IOException e) {
                if (!closed) {
                    LOG.debug("{}: a delayed reply could not be sent: {}", inner.describe(), e.getMessage());
                }
            }
            return 1;
        }

        @Override
        public void onDeath(Throwable failure) {
            died(failure);
        }
    }

    /**
     * The pump or the sender died: the link closes, reads end with an error naming why, and the
     * other thread ends its loop at its next round. Must not throw.
     */
    private void died(Throwable failure) {
        if (death == null) {
            death = failure;
        }
        closed = true;
        inner.close();
        lock.lock();
        try {
            inboundChanged.signalAll();
            outboundChanged.signalAll();
        } finally {
            lock.unlock();
        }
    }

    /** @return the exception a read or write on the closed link throws: naming what killed a thread of it, if one died */
    private IOException closedError() {
        Throwable d = death;
        return d == null ? new IOException(describe() + " is closed")
                : new IOException(describe() + " is closed: its pump or sender thread died of " + d, d);
    }

    @Override
    public void open() throws IOException {
        inner.open();
    }

    @Override
    public boolean isOpen() {
        return !closed && inner.isOpen();
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        if (closed) {
            throw closedError();
        }
        if (inline) {
            Chunk c = onWire(Arrays.copyOfRange(data, off, off + len), false);
            waitUntil(dueAt(c, len - 1));
            inner.write(data, off, len);
            return;
        }
        lock.lock();
        try {
            outbound.add(onWire(Arrays.copyOfRange(data, off, off + len), false));
            outboundChanged.signalAll();
        } finally {
            lock.unlock();
        }
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        if (closed) {
            throw closedError();
        }
        return inline ? readInline(buf, off, len, timeout) : readQueued(buf, off, len, timeout);
    }

    /** Without latency: the emulator's own thread reads a whole chunk, then hands its bytes out as each arrives. */
    private int readInline(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Chunk head = inbound.peekFirst();
        if (head == null) {
            int n = inner.read(inlineBuffer, 0, inlineBuffer.length, timeout);
            if (n <= 0) {
                return n;
            }
            head = onWire(Arrays.copyOf(inlineBuffer, n), true);
            inbound.add(head);
        }
        waitUntil(dueAt(head, head.consumed));
        return take(head, buf, off, len, System.nanoTime());
    }

    private int readQueued(byte[] buf, int off, int len, Duration timeout) throws IOException {
        long deadline = System.nanoTime() + timeout.toNanos();
        lock.lock();
        try {
            while (true) {
                if (closed) {
                    throw closedError();
                }
                Chunk head = inbound.peekFirst();
                long now = System.nanoTime();
                if (head != null && head.lost != null && head.startAt <= now) {
                    inbound.pollFirst();
                    throw head.lost;
                }
                if (head != null && head.lost == null && dueAt(head, head.consumed) <= now) {
                    return take(head, buf, off, len, now);
                }
                if (deadline - now <= 0) {
                    return 0;
                }
                long wait = deadline - now;
                if (head != null) {
                    wait = Math.min(wait, (head.lost != null ? head.startAt : dueAt(head, head.consumed)) - now);
                }
                try {
                    inboundChanged.awaitNanos(wait);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    throw new IOException(describe() + ": interrupted while reading", e);
                }
            }
        } finally {
            lock.unlock();
        }
    }

    /** Hands out the head chunk's bytes that have arrived by now, at most len; the chunk goes when spent. */
    private int take(Chunk head, byte[] buf, int off, int len, long now) {
        int arrived = byteNanos == 0 ? head.bytes.length
                : (int) Math.min(head.bytes.length, Math.max(head.consumed + 1, (now - head.startAt) / byteNanos));
        int n = Math.min(len, arrived - head.consumed);
        System.arraycopy(head.bytes, head.consumed, buf, off, n);
        head.consumed += n;
        lastDeliveredAt = dueAt(head, head.consumed - 1);
        if (head.consumed == head.bytes.length) {
            inbound.pollFirst();
        }
        return n;
    }

    private static void waitUntil(long at) {
        for (long left = at - System.nanoTime(); left > 0; left = at - System.nanoTime()) {
            LockSupport.parkNanos(left);
        }
    }

    /**
     * @return when the last byte the last {@link #read} returned arrived over the modelled link
     *         (not when the reading thread got to it: on a loaded host that can be later)
     */
    long lastDeliveredAt() {
        return lastDeliveredAt;
    }

    /** @return when the last bytes read from the real link were put on the modelled link (its arrivals count from then) */
    long lastInboundAt() {
        return lastInboundAt;
    }

    @Override
    public String describe() {
        return inner.describe() + " (" + model + ")";
    }

    @Override
    public void close() {
        closed = true;
        inner.close();
        if (inline) {
            return;
        }
        lock.lock();
        try {
            inboundChanged.signalAll();
            outboundChanged.signalAll();
        } finally {
            lock.unlock();
        }
        pump.close();
        sender.close();
    }
}
