package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.Address;

import java.util.concurrent.CompletableFuture;

/** A channel this node opened to an address, for sending messages and subscriptions there. */
public interface Link extends Channel, AutoCloseable {

    /** @return the address it was opened to */
    Address address();

    /**
     * Lets a thread that waits for a reply coming on this link receive the link's frames itself
     * while no other thread does (leader/follower), so that the reply reaches it without a hand-off
     * from the link's receiving thread: a synchronous request/reply then costs the thread wake-ups
     * of a plain socket's. Returns when {@code reply} is done, the deadline passes, the thread is
     * interrupted, or the link will not let it receive any more (a frame for a listener came, which
     * stays with the link's receiving thread and everything behind it, in order; or the link
     * closed); the caller then waits on {@code reply} as usual. The default receives nothing and
     * returns at once.
     *
     * @param reply         what the calling thread waits for
     * @param deadlineNanos when to stop, on the {@link System#nanoTime()} scale
     */
    default void receiveUntil(CompletableFuture<?> reply, long deadlineNanos) {
    }

    /** Closes it. Idempotent. */
    @Override
    void close();
}
