package io.robomw.agents.messaging;

import java.util.Map;

/**
 * A snapshot of a node's counters.
 *
 * @param framesIn        frames received and accepted
 * @param framesOut       frames handed to transports
 * @param dropped         frames dropped, by reason (every reason present, most 0)
 * @param framesLost      frames missing from datagram streams (gaps in stream sequence numbers)
 * @param framesReordered frames that arrived after a later one of their stream
 * @param listenerErrors  exceptions thrown by listeners (logged; the listener stays registered)
 */
public record MessagingStats(long framesIn, long framesOut, Map<DropReason, Long> dropped, long framesLost,
                             long framesReordered, long listenerErrors) {

    /** Copies the map. */
    public MessagingStats {
        dropped = Map.copyOf(dropped);
    }

    /**
     * @param reason a reason
     * @return how many frames were dropped for it
     */
    public long dropped(DropReason reason) {
        return dropped.getOrDefault(reason, 0L);
    }

    /** @return frames dropped for any reason */
    public long droppedTotal() {
        return dropped.values().stream().mapToLong(Long::longValue).sum();
    }
}
