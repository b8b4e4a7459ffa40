package io.robomw.cli.agents;

import io.robomw.api.Agent;

/** Test agent for mw dispatch: reports and brings home the name of each host it visits. */
public class HelloAgent extends Agent {

    private static final long serialVersionUID = 1L;

    @Override
    public void run() {
        context().report("hello from " + context().hostName());
        context().setResult("visited " + context().hostName());
    }
}
