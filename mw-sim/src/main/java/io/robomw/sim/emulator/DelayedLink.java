package io.robomw.sim.emulator;

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
import java.util.concurrent.locks.ReentrantLock;

/**
 * An emulator's end of a link, slowed down to a {@link LinkModel}: two delay lines over the real
 * link (a pseudo-terminal or a TCP server). What the driver writes is read off the real link at
 * once by a pump thread, stamped with the time it would arrive over the modelled link, and handed
 * to the emulator's {@link #read} only then; what the emulator {@link #write}s is queued and put on
 * the real link by a sender thread when it would arrive. Each direction is one wire: a chunk waits
 * until the one before it has been sent ({@code bits / baud}), then takes the latency, and
 * latencies overlap, so a batch written back to back arrives back to back.
 *
 * <p>Time is the wall clock: a link's delay is physical time, as a brick's is.
 *
 * <p>A peer that leaves (a TCP client) reaches the emulator as the {@link LinkLostException} it
 * would have got from the real link, after the bytes that came before it; replies still queued for
 * that peer are dropped, and the pump goes on reading, which accepts the next peer.
 *
 * <p>Threads: one thread may read while another writes, as {@link Link} allows; the pump and
 * sender threads ({@code <link>-in}, {@code <link>-out}) end on {@link #close()}. A model without
 * latency (a plain serial line) needs neither: the reading and writing threads wait out the bytes'
 * time themselves.
 */
final class DelayedLink implements Link {

    private static final Logger LOG = LoggerFactory.getLogger(DelayedLink.class);
    private static final Duration PUMP_POLL = Duration.ofMillis(50);
    private static final int CHUNK_BYTES = 4096;

    private final Link inner;
    private final LinkModel model;
    private final ReentrantLock lock = new ReentrantLock();
    private final Condition inboundChanged = lock.newCondition();
    private final Condition outboundChanged = lock.newCondition();
    private final Deque<Chunk> inbound = new ArrayDeque<>();
    private final Deque<Chunk> outbound = new ArrayDeque<>();
    private final Thread pump;
    private final Thread sender;
    private long inboundWireFree;
    private long outboundWireFree;
    private volatile long lastDeliveredAt = System.nanoTime();
    private volatile boolean closed;

    /** Bytes that arrive at {@code deliverAt}, or (with {@code lost} set) the news that the peer left. */
    private static final class Chunk {
        final byte[] bytes;
        final long deliverAt;
        final LinkLostException lost;
        int consumed;

        Chunk(byte[] bytes, long deliverAt, LinkLostException lost) {
            this.bytes = bytes;
            this.deliverAt = deliverAt;
            this.lost = lost;
        }
    }

    /**
     * Starts the pump and sender threads over an open link.
     *
     * @param inner the real link, open
     * @param model how slow to make it
     */
    DelayedLink(Link inner, LinkModel model) {
        this.inner = inner;
        this.model = model;
        this.inline = model.latency().isZero();
        if (inline) {
            this.pump = null;
            this.sender = null;
            return;
        }
        this.pump = new Thread(this::pump, inner.describe() + "-in");
        this.sender = new Thread(this::send, inner.describe() + "-out");
        pump.setDaemon(true);
        sender.setDaemon(true);
        pump.start();
        sender.start();
    }

    /**
     * Without latency a link is a plain serial line: the emulator's own thread reads each chunk
     * as it comes and waits out the time its bytes take, and waits out a reply's bytes before
     * writing it. No threads of its own, so a loaded host holds up one thread, not three.
     */
    private final boolean inline;

    private int readInline(byte[] buf, int off, int len, Duration timeout) throws IOException {
        int n = inner.read(buf, off, len, timeout);
        if (n > 0) {
            long now = System.nanoTime();
            long at = Math.max(now, inboundWireFree) + model.transmissionNanos(n);
            inboundWireFree = at;
            lastDeliveredAt = at;
            waitUntil(at);
        }
        return n;
    }

    private void writeInline(byte[] data, int off, int len) throws IOException {
        long now = System.nanoTime();
        long at = Math.max(now, outboundWireFree) + model.transmissionNanos(len);
        outboundWireFree = at;
        waitUntil(at);
        inner.write(data, off, len);
    }

    private static void waitUntil(long at) {
        for (long left = at - System.nanoTime(); left > 0; left = at - System.nanoTime()) {
            java.util.concurrent.locks.LockSupport.parkNanos(left);
        }
    }

    /** When a chunk of {@code n} bytes handed over now arrives, given when its wire is next free. */
    private long arrival(long now, long wireFree, int n) {
        long start = Math.max(now, wireFree);
        return start + model.transmissionNanos(n) + model.latency().toNanos();
    }

    private void pump() {
        byte[] buf = new byte[CHUNK_BYTES];
        while (!closed) {
            try {
                int n = inner.read(buf, 0, buf.length, PUMP_POLL);
                if (n <= 0) {
                    continue;
                }
                long now = System.nanoTime();
                lock.lock();
                try {
                    long at = arrival(now, inboundWireFree, n);
                    inboundWireFree = Math.max(now, inboundWireFree) + model.transmissionNanos(n);
                    inbound.add(new Chunk(Arrays.copyOf(buf, n), at, null));
                    inboundChanged.signalAll();
                } finally {
                    lock.unlock();
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
                if (!closed) {
                    LOG.debug("{}: the link closed under the pump: {}", inner.describe(), e.getMessage());
                }
                return;
            }
        }
    }

    private void send() {
        while (!closed) {
            Chunk next;
            lock.lock();
            try {
                next = outbound.peekFirst();
                long wait = next == null ? Long.MAX_VALUE : next.deliverAt - System.nanoTime();
                if (next == null || wait > 0) {
                    if (next == null) {
                        outboundChanged.await();
                    } else {
                        outboundChanged.awaitNanos(wait);
                    }
                    continue;
                }
                outbound.pollFirst();
            } catch (InterruptedException e) {
                return;
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
        }
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
            throw new IOException(describe() + " is closed");
        }
        if (inline) {
            writeInline(data, off, len);
            return;
        }
        long now = System.nanoTime();
        lock.lock();
        try {
            long at = arrival(now, outboundWireFree, len);
            outboundWireFree = Math.max(now, outboundWireFree) + model.transmissionNanos(len);
            outbound.add(new Chunk(Arrays.copyOfRange(data, off, off + len), at, null));
            outboundChanged.signalAll();
        } finally {
            lock.unlock();
        }
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        if (closed) {
            throw new IOException(describe() + " is closed");
        }
        if (inline) {
            return readInline(buf, off, len, timeout);
        }
        long deadline = System.nanoTime() + timeout.toNanos();
        lock.lock();
        try {
            while (true) {
                if (closed) {
                    throw new IOException(describe() + " is closed");
                }
                Chunk head = inbound.peekFirst();
                long now = System.nanoTime();
                if (head != null && head.deliverAt <= now) {
                    if (head.lost != null) {
                        inbound.pollFirst();
                        throw head.lost;
                    }
                    int n = Math.min(len, head.bytes.length - head.consumed);
                    System.arraycopy(head.bytes, head.consumed, buf, off, n);
                    lastDeliveredAt = head.deliverAt;
                    head.consumed += n;
                    if (head.consumed == head.bytes.length) {
                        inbound.pollFirst();
                    }
                    return n;
                }
                long wait = deadline - now;
                if (head != null) {
                    wait = Math.min(wait, head.deliverAt - now);
                }
                if (deadline - now <= 0) {
                    return 0;
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

    /**
     * @return when the bytes the last {@link #read} returned arrived over the modelled link (not
     *         when the reading thread got to them: on a loaded host that can be later)
     */
    long lastDeliveredAt() {
        return lastDeliveredAt;
    }

    @Override
    public String describe() {
        return inner.describe() + " (" + model + ")";
    }

    @Override
    public void close() {
        closed = true;
        inner.close();
        lock.lock();
        try {
            inboundChanged.signalAll();
            outboundChanged.signalAll();
        } finally {
            lock.unlock();
        }
        if (inline) {
            return;
        }
        sender.interrupt();
        for (Thread t : new Thread[]{pump, sender}) {
            if (t != Thread.currentThread()) {
                try {
                    t.join(2000);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            }
        }
    }
}
