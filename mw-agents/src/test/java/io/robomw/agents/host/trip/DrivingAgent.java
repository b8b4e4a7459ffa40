package io.robomw.agents.host.trip;

import io.robomw.api.Agent;

/** Test agent: drives its host's robot 1 m at 0.1 m/s (ten seconds, or until its command is ended), then reports "drove". */
public class DrivingAgent extends Agent {

    private static final long serialVersionUID = 1L;

    @Override
    public void run() {
        context().report("driving");
        context().robot().move(1.0, 0.1);
        context().report("drove");
    }
}
