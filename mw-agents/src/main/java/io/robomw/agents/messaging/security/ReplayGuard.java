package io.robomw.agents.messaging.security;

import java.util.LinkedHashMap;
import java.util.Map;

/**
 * Rejects authenticated frames seen before. Each source (sending node instance) has a sliding
 * window of the last {@value #WINDOW} message numbers: a number already in the window, or below
 * it, is a replay. Frames from a source are numbered in the order they were made, and may arrive
 * somewhat out of order (several threads, several links); the window absorbs that.
 *
 * <p>What it does not do: it forgets sources beyond the {@value #MAX_SOURCES} most recently seen,
 * and everything when the node restarts. The timestamp check ({@link #fresh}) bounds what can be
 * replayed then to frames younger than the allowed clock skew.
 *
 * <p>Only frames whose MAC verified may be given to it, so forged sources cannot evict real ones.
 * Thread-safe.
 */
public final class ReplayGuard {

    /** Width of each source's window, in message numbers. */
    public static final int WINDOW = 4096;
    /** How many sources are remembered. */
    public static final int MAX_SOURCES = 4096;

    private final Map<Long, Window> sources = new LinkedHashMap<>(64, 0.75f, true) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<Long, Window> eldest) {
            return size() > MAX_SOURCES;
        }
    };

    /**
     * Records a frame and says whether it is new.
     *
     * @param source        the frame's source
     * @param messageNumber its message number
     * @return {@code true} if it was not seen before; {@code false} for a replay
     */
    public boolean accept(long source, long messageNumber) {
        synchronized (sources) {
            return sources.computeIfAbsent(source, s -> new Window()).accept(messageNumber);
        }
    }

    /**
     * Says whether a frame would be a replay, without recording it (for checking before the
     * costlier MAC; only {@link #accept} records).
     *
     * @param source        the frame's source
     * @param messageNumber its message number
     * @return {@code true} if it was accepted before or is below the source's window
     */
    public boolean seen(long source, long messageNumber) {
        synchronized (sources) {
            Window w = sources.get(source);
            return w != null && w.seen(messageNumber);
        }
    }

    /**
     * @param timestampMicros the frame's timestamp
     * @param nowMicros       this host's clock
     * @param maxSkewMicros   how far apart they may be, either way
     * @return whether the frame is recent enough to be accepted
     */
    public static boolean fresh(long timestampMicros, long nowMicros, long maxSkewMicros) {
        return Math.abs(nowMicros - timestampMicros) <= maxSkewMicros;
    }

    /** The window of one source: the highest number seen and a bitmap of the {@value #WINDOW} below it. */
    private static final class Window {
        private final long[] bits = new long[WINDOW / 64];
        private long highest = Long.MIN_VALUE;

        boolean accept(long n) {
            if (highest == Long.MIN_VALUE) {
                highest = n;
                set(n);
                return true;
            }
            if (n > highest) {
                long shift = n - highest;
                if (shift >= WINDOW) {
                    java.util.Arrays.fill(bits, 0);
                } else {
                    for (long i = highest + 1; i < n; i++) {
                        clear(i);
                    }
                }
                highest = n;
                set(n);
                return true;
            }
            if (highest - n >= WINDOW) {
                return false;
            }
            if (isSet(n)) {
                return false;
            }
            set(n);
            return true;
        }

        boolean seen(long n) {
            if (highest == Long.MIN_VALUE || n > highest) {
                return false;
            }
            return highest - n >= WINDOW || isSet(n);
        }

        private int index(long n) {
            return (int) Math.floorMod(n, (long) WINDOW);
        }

        private boolean isSet(long n) {
            int i = index(n);
            return (bits[i >>> 6] & (1L << (i & 63))) != 0;
        }

        private void set(long n) {
            int i = index(n);
            bits[i >>> 6] |= 1L << (i & 63);
        }

        private void clear(long n) {
            int i = index(n);
            bits[i >>> 6] &= ~(1L << (i & 63));
        }
    }
}
