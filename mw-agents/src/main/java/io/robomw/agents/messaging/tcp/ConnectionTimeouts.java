package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.PeerLimits;

import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;

/**
 * The first-frame and idle timeouts ({@link PeerLimits}) of a transport's plain connections,
 * enforced by one timer thread that looks at every connection a few times per timeout and closes
 * one that has delivered no whole frame in time.
 *
 * <p>Why a timer and not the socket's read timeout ({@code SO_TIMEOUT}): a Java socket with a read
 * timeout is switched to non-blocking mode for good, and every read becomes a failed read, a
 * {@code poll} and a second read; on a request/reply link that doubled the reading threads' system
 * calls and made a round trip about 4 µs slower on a loaded machine (docs/messaging.md). A reader that blocks
 * in {@code read} costs one call, and its progress (a counter it bumps twice per frame, with a
 * plain store) is all the timer needs. TLS connections keep the read timeout: closing a TLS socket
 * may wait for the TLS layer's locks, which a timer thread must not do.
 *
 * <p>A timeout is detected between the limit and the limit plus one period (a tenth of the
 * shorter timeout, 10 ms to 1 s). Thread-safe.
 */
final class ConnectionTimeouts implements AutoCloseable {


    /** What the timer watches: a connection's reading progress, and how to end it. */
    interface Watched {
        /**
         * @return how far the reader got: twice the whole frames it took, plus one while the node
         *         handles the last (a listener's time is not the peer's silence)
         */
        long progress();

        /**
         * Ends the connection: the limit passed without a whole frame.
         *
         * @param firstFrame whether it was the first-frame timeout
         * @param limitNanos the timeout that passed
         */
        void timedOut(boolean firstFrame, long limitNanos);
    }

    /** What the timer saw of one connection last time (touched by the timer thread only). */
    private static final class Seen {
        long progress;
        long sinceNanos;

        Seen(long sinceNanos) {
            this.sinceNanos = sinceNanos;
        }
    }

    private final long firstFrameNanos;
    private final long idleNanos;
    private final long periodNanos;
    private final ConcurrentHashMap<Watched, Seen> watched = new ConcurrentHashMap<>();
    private final ScheduledExecutorService timer;

    /**
     * @param limits  the timeouts
     * @param threads  makes the timer thread (started at once)
     * @param failures where a failed check goes (the next period checks again)
     */
    ConnectionTimeouts(PeerLimits limits, ThreadFactory threads, io.robomw.api.spi.FailurePolicy failures) {
        this.firstFrameNanos = limits.firstFrameTimeout().toNanos();
        this.idleNanos = limits.idleTimeout().toNanos();
        this.periodNanos = Math.max(TimeUnit.MILLISECONDS.toNanos(10),
                Math.min(TimeUnit.SECONDS.toNanos(1), Math.min(firstFrameNanos, idleNanos) / 10));
        this.timer = Executors.newSingleThreadScheduledExecutor(threads);
        // A throw out of a fixed-delay task would cancel it without a word, and the node's timeouts would stop
        // being enforced: each round's failure is reported and the next period checks again.
        timer.scheduleWithFixedDelay(io.robomw.agents.net.OwnerThreads.rounds(failures, this::check), periodNanos, periodNanos, TimeUnit.NANOSECONDS);
    }

    /**
     * Watches a connection from now (its first frame is due within the first-frame timeout).
     *
     * @param c the connection
     */
    void watch(Watched c) {
        watched.put(c, new Seen(System.nanoTime()));
    }

    /** @param c a connection that closed */
    void forget(Watched c) {
        watched.remove(c);
    }

    /** @return the watched connections (for tests) */
    Set<Watched> watched() {
        return watched.keySet();
    }

    @Override
    public void close() {
        timer.shutdownNow();
        watched.clear();
    }

    private void check() {
        long now = System.nanoTime();
        watched.forEach((c, seen) -> {
            long p = c.progress();
            if (p != seen.progress) {
                seen.progress = p;
                seen.sinceNanos = now;
            } else if ((p & 1) == 0) {
                long limit = p == 0 ? firstFrameNanos : idleNanos;
                if (now - seen.sinceNanos >= limit) {
                    watched.remove(c);
                    c.timedOut(p == 0, limit);
                }
            }
        });
    }
}
