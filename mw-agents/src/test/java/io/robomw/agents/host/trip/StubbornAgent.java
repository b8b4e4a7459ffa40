package io.robomw.agents.host.trip;

import io.robomw.api.Agent;
import io.robomw.api.AgentMessage;

/**
 * Test agent whose stop ignores interrupts: it reports "waiting" home once its stop's work has
 * begun, waits (up to 30 s) for a "release" message, and counts the interrupts it swallowed
 * meanwhile; its result is that count.
 */
public class StubbornAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private transient volatile boolean released;

    @Override
    public void run() {
        int interrupts = 0;
        context().report("waiting"); // a retract asked from now on finds its callback running
        long deadline = System.nanoTime() + 30_000_000_000L;
        synchronized (this) {
            while (!released && System.nanoTime() < deadline) {
                try {
                    wait(100);
                } catch (InterruptedException e) {
                    interrupts++; // swallowed: this agent does not answer its interrupt
                }
            }
        }
        context().setResult(interrupts);
    }

    @Override
    public boolean handleMessage(AgentMessage message) {
        if ("release".equals(message.content())) {
            synchronized (this) {
                released = true;
                notifyAll();
            }
            return true;
        }
        return false;
    }
}
