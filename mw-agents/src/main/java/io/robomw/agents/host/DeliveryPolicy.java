package io.robomw.agents.host;

import java.time.Duration;

/**
 * How a host delivers what it owes agents' homes (reports and results) when a home does not
 * answer: it retries with pauses that double from 100 ms up to {@code maxBackoff}, gives up on a
 * delivery owed longer than {@code expiry} (counted from when it was first owed, across restarts
 * of a host with a durable store; the delivery is then dropped with a WARN line naming the agent
 * and what was lost), and says that a home does not answer once, then again at most every
 * {@code logInterval} while it still does not.
 *
 * @param expiry      how long a delivery is owed before the host gives up on it (default 24 h)
 * @param maxBackoff  the longest pause between two tries to a home that does not answer (default 30 s)
 * @param logInterval how often a home that still does not answer is logged again (default 5 min)
 */
public record DeliveryPolicy(Duration expiry, Duration maxBackoff, Duration logInterval) {

    /** The first pause after a failed try; each next one doubles, up to {@link #maxBackoff}. */
    public static final Duration FIRST_BACKOFF = Duration.ofMillis(100);

    /** Checks the durations: each must be positive. */
    public DeliveryPolicy {
        check("expiry", expiry);
        check("maxBackoff", maxBackoff);
        check("logInterval", logInterval);
    }

    /** @return 24 h expiry, 30 s longest back-off, a log line per home every 5 min at most */
    public static DeliveryPolicy defaults() {
        return new DeliveryPolicy(Duration.ofHours(24), Duration.ofSeconds(30), Duration.ofMinutes(5));
    }

    /** @param expiry how long a delivery is owed before it is given up @return this policy with that expiry */
    public DeliveryPolicy withExpiry(Duration expiry) {
        return new DeliveryPolicy(expiry, maxBackoff, logInterval);
    }

    /** @param maxBackoff the longest pause between tries @return this policy with that pause */
    public DeliveryPolicy withMaxBackoff(Duration maxBackoff) {
        return new DeliveryPolicy(expiry, maxBackoff, logInterval);
    }

    /** @param logInterval how often a home that does not answer is logged again @return this policy with that interval */
    public DeliveryPolicy withLogInterval(Duration logInterval) {
        return new DeliveryPolicy(expiry, maxBackoff, logInterval);
    }

    private static void check(String name, Duration d) {
        if (d == null || d.isNegative() || d.isZero()) {
            throw new IllegalArgumentException(d + " was given for " + name + ": " + name + " must be a positive duration");
        }
    }
}
