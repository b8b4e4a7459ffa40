package io.robomw.platform.mavlink.wire;

import java.time.Instant;

/**
 * The time base of message signing: 48-bit timestamps in units of 10 µs since
 * 2015-01-01 00:00:00 UTC (Unix time {@value #EPOCH_UNIX_SECONDS}). Stateless.
 */
public final class SigningTime {

    /** 2015-01-01T00:00:00Z in Unix seconds. */
    public static final long EPOCH_UNIX_SECONDS = 1_420_070_400L;
    /** Timestamp units per second. */
    public static final long UNITS_PER_SECOND = 100_000L;
    /** The largest timestamp (48 bits). */
    public static final long MAX = (1L << 48) - 1;
    /** One minute in timestamp units: how far behind a new stream may start. */
    public static final long ONE_MINUTE = 60 * UNITS_PER_SECOND;

    private SigningTime() {
    }

    /**
     * @param instant a time
     * @return its signing timestamp (0 before 2015)
     */
    public static long of(Instant instant) {
        long seconds = instant.getEpochSecond() - EPOCH_UNIX_SECONDS;
        if (seconds < 0) {
            return 0;
        }
        return Math.min(MAX, seconds * UNITS_PER_SECOND + instant.getNano() / 10_000);
    }
}
