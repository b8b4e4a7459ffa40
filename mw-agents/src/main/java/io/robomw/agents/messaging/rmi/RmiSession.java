package io.robomw.agents.messaging.rmi;

import io.robomw.agents.messaging.io.OutboundBuffer;
import io.robomw.agents.messaging.spi.Channel;

import java.io.IOException;

/**
 * A client's session at an RMI endpoint: the channel answers and publications for that client go
 * on. They wait in an {@link OutboundBuffer} until the client polls.
 */
final class RmiSession implements Channel {

    private final long id;
    private final String peer;
    private final OutboundBuffer outbound;
    private final java.util.function.Consumer<RmiSession> onClose;
    private volatile long lastPollNanos = System.nanoTime();
    private volatile Thread delivering;

    RmiSession(long id, String peer, OutboundBuffer outbound, java.util.function.Consumer<RmiSession> onClose) {
        this.id = id;
        this.peer = peer;
        this.outbound = outbound;
        this.onClose = onClose;
    }

    long id() {
        return id;
    }

    OutboundBuffer outbound() {
        return outbound;
    }

    void polled() {
        lastPollNanos = System.nanoTime();
    }

    long lastPollNanos() {
        return lastPollNanos;
    }

    void delivering(Thread t) {
        delivering = t;
    }

    @Override
    public String peer() {
        return peer;
    }

    @Override
    public void send(byte[] frame) throws IOException {
        outbound.send(frame);
    }

    @Override
    public boolean isOpen() {
        return !outbound.isClosed();
    }

    @Override
    public boolean isConnection() {
        return true;
    }

    @Override
    public boolean deliversOn(Thread thread) {
        return thread == delivering;
    }

    @Override
    public void close() {
        if (!outbound.isClosed()) {
            outbound.close();
            onClose.accept(this);
        }
    }

    @Override
    public String toString() {
        return "RmiSession[" + peer + "]";
    }
}
