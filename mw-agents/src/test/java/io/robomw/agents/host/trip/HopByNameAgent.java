package io.robomw.agents.host.trip;

import io.robomw.api.Agent;

import java.util.ArrayList;

/** Test agent: at its first stop it dispatches itself to a host given by name; brings home the hosts it visited. */
public class HopByNameAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private final String next;
    private final ArrayList<String> visited = new ArrayList<>();

    /** @param next the name of the host to go to from the first stop */
    public HopByNameAgent(String next) {
        this.next = next;
    }

    @Override
    public void run() {
        visited.add(context().hostName());
        if (visited.size() == 1) {
            context().dispatch(next);
        }
        context().setResult(new ArrayList<>(visited));
    }
}
