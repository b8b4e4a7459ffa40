package io.robomw.cli.agents;

import io.robomw.api.Agent;

/** Test agent for mw retract: notes where it began, then works for a minute (an interrupt ends it). */
public class HoldingAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private String began;

    @Override
    public void run() {
        began = "at " + context().hostName();
        try {
            Thread.sleep(60_000); // the stop's long work
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
