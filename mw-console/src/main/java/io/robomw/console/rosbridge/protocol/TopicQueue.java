package io.robomw.console.rosbridge.protocol;

import io.robomw.console.rosbridge.graph.Publication;
import io.robomw.console.rosbridge.graph.TopicListener;

import java.util.ArrayDeque;

/**
 * One client's queue for one topic: what the topic publishes waits here until the client takes
 * it, within the bounds {@link Outbox} describes. Its fields are guarded by its outbox's lock.
 */
public final class TopicQueue implements TopicListener {

    final Outbox outbox;
    final String clientTopic;
    final ArrayDeque<Outbox.Queued> messages = new ArrayDeque<>();
    int capacity;
    boolean queueing;
    long throttleNanos;
    volatile Compression compression = Compression.NONE;
    boolean inReady;
    boolean removed;
    boolean acceptedOnce;
    long lastAccepted;
    boolean sentOnce;
    long lastSent;
    long dropped;
    long throttled;

    TopicQueue(Outbox outbox, String clientTopic) {
        this.outbox = outbox;
        this.clientTopic = clientTopic;
    }

    @Override
    public void deliver(Publication publication) {
        outbox.offer(this, publication);
    }

    /** @return the messages this queue dropped because the client did not keep up */
    public long dropped() {
        synchronized (outbox) {
            return dropped;
        }
    }
}
