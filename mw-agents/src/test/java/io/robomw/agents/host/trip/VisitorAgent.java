package io.robomw.agents.host.trip;

import io.robomw.api.Agent;
import io.robomw.api.AgentMessage;

import java.io.Serializable;
import java.util.ArrayList;

/** Test agent: records the hosts it visits and brings the list home; answers "where" messages. */
public class VisitorAgent extends Agent {

    private static final long serialVersionUID = 1L;

    private final ArrayList<String> visited = new ArrayList<>();
    private byte[] payload = new byte[0];
    private Serializable extra;
    /** How long each stop blocks, waiting on a message that releases it (0: not at all). */
    private boolean holdUntilReleased;
    private transient volatile boolean released;

    public VisitorAgent payload(int bytes) {
        payload = new byte[bytes];
        return this;
    }

    /** Carries any value, for tests of what hosts refuse. */
    public VisitorAgent extra(Serializable value) {
        extra = value;
        return this;
    }

    public VisitorAgent holdUntilReleased() {
        holdUntilReleased = true;
        return this;
    }

    @Override
    public void run() {
        synchronized (this) {
            visited.add(context().hostName());
        }
        context().report("at " + context().hostName());
        context().setResult(new ArrayList<>(visited));
        if (holdUntilReleased) {
            long deadline = System.nanoTime() + 120_000_000_000L; // longer than any test waits: only a release or an interrupt ends it
            synchronized (this) {
                while (!released && System.nanoTime() < deadline) {
                    try {
                        wait(100);
                    } catch (InterruptedException e) {
                        return;
                    }
                }
            }
        }
    }

    @Override
    public boolean handleMessage(AgentMessage message) {
        if ("where".equals(message.content())) {
            message.sendReply(context().hostName());
            return true;
        }
        if ("release".equals(message.content())) {
            synchronized (this) {
                released = true;
                notifyAll();
            }
            return true;
        }
        return false;
    }

    public synchronized ArrayList<String> visited() {
        return new ArrayList<>(visited);
    }

    public int payloadSize() {
        return payload.length;
    }
}
