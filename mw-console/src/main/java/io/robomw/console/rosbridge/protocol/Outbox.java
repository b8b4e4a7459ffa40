package io.robomw.console.rosbridge.protocol;

import io.robomw.console.rosbridge.graph.Publication;
import io.robomw.console.rosbridge.msg.Wire;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.ArrayDeque;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * Everything waiting to go to one client, bounded, handed to the connection as the client takes
 * it (at most {@value #MAX_IN_FLIGHT} frames on their way at once). A slow client never costs the server more than {@link Limits#maxClientBytes}: each of its
 * subscriptions ({@link TopicQueue}) holds at most its {@code queue_length} messages (or
 * {@link Limits#maxQueue} for 0), and a full one drops its oldest, as rosbridge_suite's queue
 * does. Replies and status messages ({@link #reply}) are never dropped; a client that lets more
 * than {@link Limits#maxControlFrames} of them pile up is disconnected.
 *
 * <h2>Order of sending</h2>
 * The rest of a fragmented message first, then replies, then subscriptions' messages, one per
 * subscription in turn. A subscription with a {@code throttle_rate} and a {@code queue_length}
 * sends at most one message per throttle period (a timer wakes it); one with a throttle and no
 * queue drops the messages that arrive within the period after the last one it took, as
 * rosbridge_suite's {@code ThrottleMessageHandler} does.
 *
 * <h2>Fragments</h2>
 * A text frame longer than the client's {@code fragment_size} goes out as {@code fragment}
 * frames ({@code {op, id, data, num, total}}) whose {@code data} add up to the frame, as
 * rosbridge_suite's {@code Fragmentation} sends them. Binary (CBOR) frames are not fragmented.
 *
 * <p>Thread-safe: publishers on any thread, the transport's completions on any thread. Sending
 * is a drain loop, so a transport that completes sends at once does not recurse.
 */
public final class Outbox {

    private static final Logger LOG = LoggerFactory.getLogger(Outbox.class);
    /** WebSocket close code: policy violation. */
    static final int CLOSE_POLICY = 1008;
    /**
     * Frames handed to the connection and not yet written: Jetty queues them and writes several
     * together, one system call for many small messages; a client that does not read holds at
     * most this many there, the rest wait here, bounded.
     */
    static final int MAX_IN_FLIGHT = 64;

    private final Transport transport;
    private final Limits limits;
    private final ScheduledExecutorService timer;
    private final String client;
    private final AtomicInteger wip = new AtomicInteger();
    private final Runnable sent = this::sent;

    private final ArrayDeque<Frame> control = new ArrayDeque<>();
    private final ArrayDeque<Frame> fragments = new ArrayDeque<>();
    private final ArrayDeque<TopicQueue> ready = new ArrayDeque<>();
    private int inFlight;
    private boolean closed;
    private long queuedChars;
    private int fragmentSize;
    private long fragmentIds;
    private ScheduledFuture<?> wake;
    private long wakeAt;
    private long sentFrames;
    private long dropped;

    /** A frame: text or binary. */
    record Frame(String text, byte[] binary, String id) {
    }

    /** A message in a subscription's queue, encoded as its subscription wants it, with its size. */
    record Queued(String text, byte[] binary, int size) {
    }

    /**
     * @param transport the client's connection
     * @param limits    the bounds
     * @param timer     wakes throttled subscriptions
     * @param client    the client, as log lines name it
     */
    public Outbox(Transport transport, Limits limits, ScheduledExecutorService timer, String client) {
        this.transport = transport;
        this.limits = limits;
        this.timer = timer;
        this.client = client;
    }

    /**
     * @param clientTopic the topic as the client named it (its frames carry that name)
     * @return a new, empty subscription queue, sending JSON without throttle until configured
     */
    public TopicQueue queue(String clientTopic) {
        TopicQueue q = new TopicQueue(this, clientTopic);
        synchronized (this) {
            q.capacity = limits.maxQueue();
        }
        return q;
    }

    /**
     * Sets a subscription's sending rules (the merged rules of the client's subscriptions to its topic).
     *
     * @param q             the queue
     * @param queueLength   the {@code queue_length}; 0 for none
     * @param throttleNanos the {@code throttle_rate}, in nanoseconds; 0 for none
     * @param compression   text or CBOR
     */
    void configure(TopicQueue q, int queueLength, long throttleNanos, Compression compression) {
        synchronized (this) {
            q.queueing = queueLength > 0;
            q.capacity = queueLength > 0 ? Math.min(queueLength, limits.maxQueue()) : limits.maxQueue();
            q.throttleNanos = Math.max(0, throttleNanos);
            q.compression = compression;
            while (q.messages.size() > q.capacity) {
                dropOldest(q);
            }
        }
        drain();
    }

    /**
     * Stops a subscription's queue; what it holds is dropped.
     *
     * @param q the queue
     */
    void remove(TopicQueue q) {
        synchronized (this) {
            q.removed = true;
            while (!q.messages.isEmpty()) {
                queuedChars -= q.messages.poll().size();
            }
        }
    }

    /**
     * @param size the client's {@code fragment_size}; 0 or less for none
     */
    public void fragmentSize(int size) {
        synchronized (this) {
            fragmentSize = Math.max(0, size);
        }
    }

    /**
     * Queues a reply or status message (never dropped).
     *
     * @param text the frame
     * @param id   the interaction's id, for the fragments if it is fragmented; {@code null} for none
     */
    public void reply(String text, String id) {
        boolean overflow;
        synchronized (this) {
            if (closed) {
                return;
            }
            overflow = control.size() >= limits.maxControlFrames();
            if (!overflow) {
                control.add(new Frame(text, null, id));
            }
        }
        if (overflow) {
            LOG.warn("rosbridge: {} does not read its replies ({} waiting); disconnecting it", client, limits.maxControlFrames());
            close();
            transport.close(CLOSE_POLICY, "more than " + limits.maxControlFrames() + " replies waiting: read them");
            return;
        }
        drain();
    }

    /** A subscription's message, from its topic's publishing thread. */
    void offer(TopicQueue q, Publication p) {
        synchronized (this) {
            if (closed || q.removed) {
                return;
            }
            if (q.throttleNanos > 0 && !q.queueing) {
                long now = System.nanoTime();
                if (q.acceptedOnce && now - q.lastAccepted < q.throttleNanos) {
                    q.throttled++;
                    return;
                }
                q.acceptedOnce = true;
                q.lastAccepted = now;
            }
        }
        boolean cbor = q.compression == Compression.CBOR;
        String text = cbor ? null : p.jsonFrame(q.clientTopic);
        byte[] binary = cbor ? p.cborFrame(q.clientTopic) : null;
        int size = cbor ? binary.length : text.length();
        synchronized (this) {
            if (closed || q.removed) {
                return;
            }
            while (q.messages.size() >= q.capacity) {
                dropOldest(q);
            }
            while (queuedChars + size > limits.maxClientBytes() && !q.messages.isEmpty()) {
                dropOldest(q);
            }
            if (queuedChars + size > limits.maxClientBytes()) {
                q.dropped++;
                countDrop(q);
                return;
            }
            q.messages.add(new Queued(text, binary, size));
            queuedChars += size;
            if (!q.inReady) {
                q.inReady = true;
                ready.add(q);
            }
        }
        drain();
    }

    private void dropOldest(TopicQueue q) {
        Queued old = q.messages.poll();
        if (old != null) {
            queuedChars -= old.size();
            q.dropped++;
            countDrop(q);
        }
    }

    private void countDrop(TopicQueue q) {
        dropped++;
        if (Long.bitCount(q.dropped) == 1) { // 1, 2, 4, 8...: a slow client is logged, not once per message
            LOG.info("rosbridge: {} is not keeping up with {}: {} of its messages dropped, oldest first (queue of {})", client, q.clientTopic,
                    q.dropped, q.capacity);
        }
    }

    /** @return the messages dropped for this client so far (full queues, no room left) */
    public synchronized long dropped() {
        return dropped;
    }

    /** @return the frames sent to this client so far */
    public synchronized long sentFrames() {
        return sentFrames;
    }

    /** @return characters of messages waiting */
    public synchronized long queuedChars() {
        return queuedChars;
    }

    /** Drops everything and sends nothing more. */
    public void close() {
        synchronized (this) {
            closed = true;
            control.clear();
            fragments.clear();
            for (TopicQueue q : ready) {
                q.messages.clear();
            }
            ready.clear();
            queuedChars = 0;
            if (wake != null) {
                wake.cancel(false);
                wake = null;
            }
        }
    }

    private void drain() {
        if (wip.getAndIncrement() != 0) {
            return;
        }
        int missed = 1;
        do {
            while (true) {
                Frame f;
                synchronized (this) {
                    if (closed || inFlight >= MAX_IN_FLIGHT) {
                        break;
                    }
                    f = next();
                    if (f == null) {
                        break;
                    }
                    inFlight++;
                    sentFrames++;
                }
                try {
                    if (f.binary() != null) {
                        transport.sendBinary(f.binary(), sent);
                    } else {
                        transport.sendText(f.text(), sent);
                    }
                } catch (RuntimeException e) {
                    LOG.debug("rosbridge: sending to {} failed: {}", client, e.toString());
                    synchronized (this) {
                        inFlight--;
                        closed = true;
                    }
                }
            }
            missed = wip.addAndGet(-missed);
        } while (missed != 0);
    }

    private void woken() {
        synchronized (this) {
            wake = null; // a throttled subscription sending now may need the next wake-up at once
        }
        drain();
    }

    private void sent() {
        synchronized (this) {
            inFlight--;
        }
        drain();
    }

    /** The next frame to send, or null; schedules a wake-up for throttled subscriptions. Holds the lock. */
    private Frame next() {
        if (!fragments.isEmpty()) {
            return fragments.poll();
        }
        if (!control.isEmpty()) {
            return fragmented(control.poll());
        }
        long now = System.nanoTime();
        long earliest = Long.MAX_VALUE;
        for (int i = ready.size(); i > 0; i--) {
            TopicQueue q = ready.poll();
            if (q.removed || q.messages.isEmpty()) {
                q.inReady = false;
                continue;
            }
            if (q.queueing && q.throttleNanos > 0 && q.sentOnce && now - q.lastSent < q.throttleNanos) {
                earliest = Math.min(earliest, q.lastSent + q.throttleNanos);
                ready.add(q);
                continue;
            }
            Queued m = q.messages.poll();
            queuedChars -= m.size();
            q.lastSent = now;
            q.sentOnce = true;
            if (q.messages.isEmpty()) {
                q.inReady = false;
            } else {
                ready.add(q);
            }
            return m.binary() != null ? new Frame(null, m.binary(), null) : fragmented(new Frame(m.text(), null, null));
        }
        if (earliest != Long.MAX_VALUE) {
            wakeAt(earliest, now);
        }
        return null;
    }

    private void wakeAt(long at, long now) {
        if (wake != null && !wake.isDone() && wakeAt <= at) {
            return;
        }
        if (wake != null) {
            wake.cancel(false);
        }
        wakeAt = at;
        wake = timer.schedule(this::woken, Math.max(0, at - now), TimeUnit.NANOSECONDS);
    }

    private Frame fragmented(Frame f) {
        if (fragmentSize <= 0 || f.text() == null || f.text().length() <= fragmentSize) {
            return f;
        }
        String text = f.text();
        String id = f.id() != null ? f.id() : "fragment:" + (++fragmentIds);
        int total = (text.length() + fragmentSize - 1) / fragmentSize;
        Frame first = null;
        for (int i = 0; i < total; i++) {
            Map<String, Object> frag = new LinkedHashMap<>();
            frag.put("op", "fragment");
            frag.put("id", id);
            frag.put("data", text.substring(i * fragmentSize, Math.min(text.length(), (i + 1) * fragmentSize)));
            frag.put("num", i);
            frag.put("total", total);
            Frame piece = new Frame(Wire.jsonFrame(frag), null, id);
            if (first == null) {
                first = piece;
            } else {
                fragments.add(piece);
            }
        }
        return first;
    }
}
