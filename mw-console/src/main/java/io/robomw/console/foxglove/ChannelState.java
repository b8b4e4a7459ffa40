package io.robomw.console.foxglove;

import java.util.ArrayList;
import java.util.List;

/**
 * A channel as the server keeps it: its advertisement, its subscribers (a client and the client's
 * id for the subscription), and its latest message, which a new subscriber gets at once (as a
 * latched ROS topic), so the arena sent once at a run's start reaches a client that connects
 * later. Thread-safe: publishing (the encoder thread) and subscribing (a connection's thread) take
 * its lock, so a new subscriber never gets an older message after a newer one.
 */
final class ChannelState {

    private record Subscriber(ClientSession session, long id) {
    }

    private final Channel channel;
    private final List<Subscriber> subscribers = new ArrayList<>();
    private long latestTime;
    private byte[] latest;

    ChannelState(Channel channel) {
        this.channel = channel;
    }

    /** @return what is advertised */
    Channel channel() {
        return channel;
    }

    /**
     * Sends a message to every subscriber and keeps it as the latest.
     *
     * @param logTimeNanos its log time
     * @param payload      its JSON
     * @return how many subscribers it was queued for
     */
    synchronized int publish(long logTimeNanos, byte[] payload) {
        latestTime = logTimeNanos;
        latest = payload;
        for (Subscriber s : subscribers) {
            s.session().sendData(BinaryFrames.messageData(s.id(), logTimeNanos, payload));
        }
        return subscribers.size();
    }

    /** Adds a subscriber and sends it the latest message, if there is one. */
    synchronized void subscribe(ClientSession session, long id) {
        subscribers.add(new Subscriber(session, id));
        if (latest != null) {
            session.sendData(BinaryFrames.messageData(id, latestTime, latest));
        }
    }

    /** Removes a subscriber. */
    synchronized void unsubscribe(ClientSession session, long id) {
        subscribers.remove(new Subscriber(session, id));
    }

    /** @return subscribers now */
    synchronized int subscribers() {
        return subscribers.size();
    }
}
