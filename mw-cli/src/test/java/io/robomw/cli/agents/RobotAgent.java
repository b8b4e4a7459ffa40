package io.robomw.cli.agents;

import io.robomw.api.Agent;

/** Test agent for mw dispatch: drives the host's robot (and fails at a host that has none). */
public class RobotAgent extends Agent {

    private static final long serialVersionUID = 1L;

    @Override
    public void run() {
        context().robot().move(0.1, 0.1);
    }
}
