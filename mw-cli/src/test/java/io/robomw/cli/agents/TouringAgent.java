package io.robomw.cli.agents;

import io.robomw.api.Agent;

/**
 * Test agent for mw dispatch: a clone that goes on from its first host to the host given as its
 * argument, reporting the name of each host it visits.
 */
public class TouringAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private final String next;
    private boolean extended;

    /** @param next the address of the host every clone visits after its first */
    public TouringAgent(String next) {
        this.next = next;
    }

    @Override
    public void run() {
        if (!extended) {
            context().itinerary().addStop(next);
            extended = true;
        }
        context().report("hello from " + context().hostName());
        context().setResult("last at " + context().hostName());
    }
}
