package io.robomw.console.rosbridge.protocol;

import java.time.Duration;

/**
 * What one endpoint and each of its clients may use, so that no client (slow, buggy or hostile)
 * can take the server's memory or threads. rosbridge_suite has only the first of these
 * ({@code max_message_size}); the rest are RoboMW's.
 *
 * @param maxMessageBytes          largest frame a client may send (and largest message a client's
 *                                 fragments may add up to); rosbridge_suite's default, 10,000,000
 * @param maxConnections           clients at once; one more is refused at the handshake (HTTP 503)
 * @param maxSubscriptions         subscriptions one client may hold (each {@code id} on each topic counts)
 * @param maxAdvertisements        topics one client may advertise
 * @param maxCallsInFlight         service calls of one client not yet answered; one more is answered
 *                                 {@code result: false} at once
 * @param maxQueue                 messages waiting per subscription when the client asked for
 *                                 {@code queue_length} 0 (rosbridge's "no queueing", whose socket
 *                                 buffer grows without bound), and the most any {@code queue_length}
 *                                 gets; a client that does not keep up loses the oldest
 * @param maxClientBytes           characters of messages waiting for one client in all; past it the
 *                                 oldest of the subscription being added to are dropped
 * @param maxControlFrames         replies and status messages waiting for one client; past it the
 *                                 client is disconnected (it sends requests and does not read the answers)
 * @param maxPartialMessages       messages one client may be sending in fragments at once
 * @param fragmentTimeout          how long a partly received message is kept (rosbridge_suite's
 *                                 {@code fragment_timeout}, 600 s)
 * @param maxCallDuration          longest a service call may take before it is answered {@code result: false}
 */
public record Limits(int maxMessageBytes, int maxConnections, int maxSubscriptions, int maxAdvertisements, int maxCallsInFlight,
                     int maxQueue, long maxClientBytes, int maxControlFrames, int maxPartialMessages, Duration fragmentTimeout,
                     Duration maxCallDuration) {

    /** The defaults: rosbridge_suite's where it has one. */
    public static final Limits DEFAULTS = new Limits(10_000_000, 64, 1024, 256, 64, 100, 64L << 20, 4096, 16,
            Duration.ofSeconds(600), Duration.ofMinutes(10));

    /** Checks every limit is positive. */
    public Limits {
        if (maxMessageBytes < 1024 || maxConnections < 1 || maxSubscriptions < 1 || maxAdvertisements < 1 || maxCallsInFlight < 1 || maxQueue < 1
                || maxClientBytes < 1024 || maxControlFrames < 16 || maxPartialMessages < 1 || fragmentTimeout.isNegative() || fragmentTimeout.isZero()
                || maxCallDuration.isNegative() || maxCallDuration.isZero()) {
            throw new IllegalArgumentException("every rosbridge limit must be positive (message and client bytes at least 1024, control frames at least 16): "
                    + "got " + this);
        }
    }

    /**
     * @param bytes largest frame a client may send
     * @return these limits with that one changed
     */
    public Limits withMaxMessageBytes(int bytes) {
        return new Limits(bytes, maxConnections, maxSubscriptions, maxAdvertisements, maxCallsInFlight, maxQueue, maxClientBytes, maxControlFrames,
                maxPartialMessages, fragmentTimeout, maxCallDuration);
    }

    /**
     * @param connections clients at once
     * @return these limits with that one changed
     */
    public Limits withMaxConnections(int connections) {
        return new Limits(maxMessageBytes, connections, maxSubscriptions, maxAdvertisements, maxCallsInFlight, maxQueue, maxClientBytes, maxControlFrames,
                maxPartialMessages, fragmentTimeout, maxCallDuration);
    }

    /**
     * @param subscriptions subscriptions per client
     * @return these limits with that one changed
     */
    public Limits withMaxSubscriptions(int subscriptions) {
        return new Limits(maxMessageBytes, maxConnections, subscriptions, maxAdvertisements, maxCallsInFlight, maxQueue, maxClientBytes, maxControlFrames,
                maxPartialMessages, fragmentTimeout, maxCallDuration);
    }

    /**
     * @param queue messages waiting per subscription at most
     * @return these limits with that one changed
     */
    public Limits withMaxQueue(int queue) {
        return new Limits(maxMessageBytes, maxConnections, maxSubscriptions, maxAdvertisements, maxCallsInFlight, queue, maxClientBytes, maxControlFrames,
                maxPartialMessages, fragmentTimeout, maxCallDuration);
    }

    /**
     * @param bytes characters waiting per client at most
     * @return these limits with that one changed
     */
    public Limits withMaxClientBytes(long bytes) {
        return new Limits(maxMessageBytes, maxConnections, maxSubscriptions, maxAdvertisements, maxCallsInFlight, maxQueue, bytes, maxControlFrames,
                maxPartialMessages, fragmentTimeout, maxCallDuration);
    }

    /**
     * @param calls unanswered calls per client
     * @return these limits with that one changed
     */
    public Limits withMaxCallsInFlight(int calls) {
        return new Limits(maxMessageBytes, maxConnections, maxSubscriptions, maxAdvertisements, calls, maxQueue, maxClientBytes, maxControlFrames,
                maxPartialMessages, fragmentTimeout, maxCallDuration);
    }
}
