package io.robomw.bench.jade;

import jade.core.Agent;
import jade.core.ContainerID;

import java.util.Random;

/**
 * The agent that {@link JadeMoveBaseline} times: created on its home container (A), it carries a
 * {@code byte[]} payload of the size asked for and moves to the other container (B) and back
 * with {@link #doMove}, over and over. Each round trip is timed on the home container with
 * {@link System#nanoTime()} from just before the move to B until {@link #afterMove()} on A
 * again, and handed to {@link JadeRoundTripLog} of that JVM, which says when to stop.
 *
 * <p>Arguments: payload size in bytes ({@link Integer}), the name of the container to visit
 * ({@link String}). Besides the payload, only two container names and the departure time travel.
 */
public final class JadeMoverAgent extends Agent {

    private byte[] payload;
    private String home;
    private String away;
    private long departedNanos;

    @Override
    protected void setup() {
        Object[] args = getArguments();
        payload = new byte[(Integer) args[0]];
        new Random(42).nextBytes(payload);
        away = (String) args[1];
        setArguments(null);
        home = here().getName();
        depart();
    }

    private void depart() {
        departedNanos = System.nanoTime();
        doMove(new ContainerID(away, null));
    }

    @Override
    protected void afterMove() {
        if (!home.equals(here().getName())) {
            doMove(new ContainerID(home, null));
            return;
        }
        long roundTrip = System.nanoTime() - departedNanos;
        if (JadeRoundTripLog.record(getLocalName(), roundTrip, payload.length)) {
            depart();
        } else {
            doDelete();
        }
    }
}
