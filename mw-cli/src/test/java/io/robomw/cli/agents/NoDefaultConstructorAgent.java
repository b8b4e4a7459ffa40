package io.robomw.cli.agents;

import io.robomw.api.Agent;

/** Test agent for mw dispatch: only a constructor taking a number, which the command cannot call. */
public class NoDefaultConstructorAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private final int n;

    public NoDefaultConstructorAgent(int n) {
        this.n = n;
    }

    @Override
    public void run() {
        context().setResult(n);
    }
}
