package io.robomw.agents.host.trip;

import io.robomw.api.Agent;
import io.robomw.api.AgentMessage;

/**
 * Test agent: at each stop it reports "HOST early 1" to "HOST early 3"; at the host named by
 * {@link #holdAt} it first waits for a "go" message and, after its reports, holds until it is
 * interrupted (the host closing under it), so a test can stop the host mid-stop.
 */
public class NumberedReporter extends Agent {

    private static final long serialVersionUID = 1L;

    private final String holdAt;
    private transient boolean go;

    public NumberedReporter(String holdAt) {
        this.holdAt = holdAt;
    }

    @Override
    public void run() {
        String at = context().hostName();
        boolean hold = at.equals(holdAt);
        if (hold && !waitFor(() -> go)) {
            return;
        }
        for (int i = 1; i <= 3; i++) {
            context().report(at + " early " + i);
        }
        if (hold) {
            waitFor(() -> false); // until the host interrupts the stop
        }
        context().setResult("done");
    }

    private synchronized boolean waitFor(java.util.function.BooleanSupplier condition) {
        long deadline = System.nanoTime() + 30_000_000_000L;
        while (!condition.getAsBoolean() && System.nanoTime() < deadline) {
            try {
                wait(1_000);
            } catch (InterruptedException e) {
                return false;
            }
        }
        return condition.getAsBoolean();
    }

    @Override
    public synchronized boolean handleMessage(AgentMessage message) {
        if ("go".equals(message.content())) {
            go = true;
            notifyAll();
            return true;
        }
        return false;
    }
}
