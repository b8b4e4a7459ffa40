package io.robomw.console.foxglove;

import java.nio.ByteBuffer;
import java.util.ArrayDeque;

/**
 * What is waiting to be sent to one client, as the Foxglove SDK keeps it: a <em>control</em>
 * queue (serverInfo, advertisements, status: never dropped; if it fills, the client is too slow to
 * be served and is disconnected) and a <em>data</em> queue (messages, TIME frames: bounded, a full
 * queue drops its oldest frame to take a new one, so a slow client gets the latest data and the
 * server's memory stays bounded). Control frames go out before data frames, so a channel's
 * advertisement always reaches the client before its messages.
 *
 * <p>Not thread-safe: its client session guards it.
 */
final class OutQueue {

    /** One frame: text (JSON) or binary. */
    record Frame(String text, ByteBuffer binary) {
        static Frame text(String s) {
            return new Frame(s, null);
        }

        static Frame binary(ByteBuffer b) {
            return new Frame(null, b);
        }
    }

    private final int dataLimit;
    private final int controlLimit;
    private final ArrayDeque<Frame> control = new ArrayDeque<>();
    private final ArrayDeque<Frame> data = new ArrayDeque<>();
    private long dropped;

    /**
     * @param dataLimit    data frames kept at most (the oldest goes first)
     * @param controlLimit control frames kept at most
     */
    OutQueue(int dataLimit, int controlLimit) {
        if (dataLimit < 1 || controlLimit < 1) {
            throw new IllegalArgumentException("queue limits must be >= 1, got data " + dataLimit + ", control " + controlLimit);
        }
        this.dataLimit = dataLimit;
        this.controlLimit = controlLimit;
    }

    /** Queues a data frame, dropping the oldest one if the queue is full. @param f the frame */
    void offerData(Frame f) {
        if (data.size() >= dataLimit) {
            data.pollFirst();
            dropped++;
        }
        data.addLast(f);
    }

    /**
     * Queues a control frame.
     *
     * @param f the frame
     * @return false if the control queue is full (the client must be disconnected)
     */
    boolean offerControl(Frame f) {
        if (control.size() >= controlLimit) {
            return false;
        }
        control.addLast(f);
        return true;
    }

    /** @return the next frame to send (control first), or null */
    Frame poll() {
        Frame f = control.pollFirst();
        return f != null ? f : data.pollFirst();
    }

    /** @return data frames dropped so far */
    long dropped() {
        return dropped;
    }

    /** @return frames waiting */
    int size() {
        return control.size() + data.size();
    }

    /** Forgets everything waiting (the client is gone). */
    void clear() {
        control.clear();
        data.clear();
    }
}
