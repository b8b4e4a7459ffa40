package io.robomw.bench.jade;

import jade.core.Agent;
import jade.core.ContainerID;
import jade.core.behaviours.CyclicBehaviour;

import java.util.concurrent.atomic.AtomicInteger;

/**
 * An agent of the many-agents JADE baseline that moves to one container and waits there for a
 * message (a cyclic behaviour that blocks, JADE's idle agent), counting itself in that JVM's
 * {@code robomw.bench.many.parked}. Argument: the container's name.
 */
public final class JadeParkedAgent extends Agent {

    private String target;

    @Override
    protected void setup() {
        target = (String) getArguments()[0];
        setArguments(null);
        doMove(new ContainerID(target, null));
    }

    @Override
    protected void afterMove() {
        ((AtomicInteger) System.getProperties().get("robomw.bench.many.parked")).incrementAndGet();
        addBehaviour(new Waiting());
    }

    /** Waits for a message; none comes. */
    private static final class Waiting extends CyclicBehaviour {
        @Override
        public void action() {
            if (myAgent.receive() == null) {
                block();
            }
        }
    }
}
