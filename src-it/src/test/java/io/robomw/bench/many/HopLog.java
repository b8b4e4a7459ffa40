package io.robomw.bench.many;

import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLongArray;
import java.util.function.LongPredicate;

/**
 * What one host JVM of the many-agents benchmark records: each hop's latency (from the moment the
 * agent left its last stop to the start of its work here) in a histogram of 1 µs buckets up to
 * 20 ms and 1 ms buckets up to 10 s, while the driver measures; whether agents keep hopping; how
 * many came home and how many wait here. The agents reach it through {@link System#getProperties()}
 * (JDK types only, so nothing of the benchmark travels with an agent): {@value #HOP} is a
 * {@link LongPredicate} (latency in ns, or −1 for an agent's first stop; answers whether to go on),
 * {@value #HOME} and {@value #PARKED} are {@link AtomicInteger}s, {@value #GATE} a
 * {@link java.util.concurrent.CountDownLatch} parked agents wait on, {@value #PACE} an
 * {@link java.util.concurrent.atomic.AtomicLong}: how long on average a hopping agent waits at each
 * stop before it leaves (ns; 0: it leaves at once, the saturated load).
 */
public final class HopLog implements LongPredicate {

    /** The system property an agent finds this log under. */
    public static final String HOP = "robomw.bench.many.hop";
    /** The system property of the count of agents home. */
    public static final String HOME = "robomw.bench.many.home";
    /** The system property of the count of agents waiting here. */
    public static final String PARKED = "robomw.bench.many.parked";
    /** The system property of the latch parked agents wait on. */
    public static final String GATE = "robomw.bench.many.gate";
    /** The system property of the mean wait at each stop, ns (paced mode; 0 saturates). */
    public static final String PACE = "robomw.bench.many.pace";

    static final int FINE = 20_000;
    static final int BUCKETS = FINE + 10_000;

    private final AtomicLongArray buckets = new AtomicLongArray(BUCKETS);
    private volatile boolean measuring;
    private long measureStart;
    private volatile boolean running = true;

    /** Installs a fresh log and counters in this JVM's system properties. */
    static HopLog install() {
        HopLog log = new HopLog();
        System.getProperties().put(HOP, log);
        System.getProperties().put(HOME, new AtomicInteger());
        System.getProperties().put(PARKED, new AtomicInteger());
        System.getProperties().put(GATE, new java.util.concurrent.CountDownLatch(1));
        System.getProperties().put(PACE, new java.util.concurrent.atomic.AtomicLong());
        return log;
    }

    @Override
    public boolean test(long latencyNanos) {
        if (measuring && latencyNanos >= 0) {
            buckets.incrementAndGet(bucket(latencyNanos));
        }
        return running;
    }

    static int bucket(long nanos) {
        long us = nanos / 1000;
        return us < FINE ? (int) us : (int) Math.min(BUCKETS - 1, FINE + (us - FINE) / 1000);
    }

    /** @return the upper edge of a bucket, µs */
    static double micros(int bucket) {
        return bucket < FINE ? bucket + 1 : FINE + (bucket - FINE + 1) * 1000.0;
    }

    /** Empties the histogram and starts recording. */
    void measure() {
        for (int i = 0; i < BUCKETS; i++) {
            buckets.set(i, 0);
        }
        measureStart = System.nanoTime();
        measuring = true;
    }

    /** Stops recording; agents go home at their next stop. */
    void stop() {
        measuring = false;
        running = false;
    }

    /** @return the nanoseconds recorded, then the histogram as {@code bucket:count,...} (non-empty buckets; {@code -} if none), recording stopped */
    String snapshot() {
        measuring = false;
        long window = System.nanoTime() - measureStart;
        StringBuilder b = new StringBuilder();
        for (int i = 0; i < BUCKETS; i++) {
            long n = buckets.get(i);
            if (n > 0) {
                b.append(b.length() == 0 ? "" : ",").append(i).append(':').append(n);
            }
        }
        return window + " " + (b.length() == 0 ? "-" : b.toString());
    }

    /** @param nanos the mean wait of a hopping agent at each stop from now on (0: none) */
    static void pace(long nanos) {
        ((java.util.concurrent.atomic.AtomicLong) System.getProperties().get(PACE)).set(nanos);
    }

    /**
     * The wait at a stop: uniform in [mean / 2, 3 mean / 2) by the agent's random state, so that
     * agents do not leave in step; 0 when not paced.
     *
     * @param seed the agent's random state
     * @return ns
     */
    public static long waitNanos(long seed) {
        long mean = ((java.util.concurrent.atomic.AtomicLong) System.getProperties().get(PACE)).get();
        return mean <= 0 ? 0 : mean / 2 + Math.floorMod(seed >>> 1, mean);
    }

    static AtomicInteger counter(String property) {
        return (AtomicInteger) System.getProperties().get(property);
    }
}
