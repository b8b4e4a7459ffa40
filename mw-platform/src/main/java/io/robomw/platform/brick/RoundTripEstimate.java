package io.robomw.platform.brick;

import java.util.concurrent.atomic.AtomicLong;

/**
 * A driver's running estimate of its link's round trip, from request sent to reply's first byte
 * received, smoothed as TCP smooths its round-trip time (each sample moves the estimate an eighth
 * of the way, RFC 6298). A motor platform on a slow link uses half of it as the link's one-way
 * delay, to date its encoder readings and to send stops early enough.
 *
 * <p>Time is the wall clock: a link's delay is physical time. Thread-safe.
 */
public final class RoundTripEstimate {

    private final AtomicLong smoothed = new AtomicLong(-1);

    /**
     * @param nanos one measured round trip
     */
    public void sample(long nanos) {
        if (nanos < 0) {
            return;
        }
        smoothed.updateAndGet(s -> s < 0 ? nanos : s + (nanos - s) / 8);
    }

    /** @return the smoothed round trip, nanoseconds; 0 before the first sample */
    public long nanos() {
        return Math.max(0, smoothed.get());
    }

    /** @return half the round trip: the link's one-way delay, nanoseconds */
    public long oneWayNanos() {
        return nanos() / 2;
    }
}
