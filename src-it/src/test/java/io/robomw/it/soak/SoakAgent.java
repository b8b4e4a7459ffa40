package io.robomw.it.soak;

import io.robomw.api.Agent;
import io.robomw.api.Itinerary;

import java.util.ArrayList;
import java.util.concurrent.ThreadLocalRandom;

/**
 * The soak tests' agent: goes round its hosts until a deadline. At each stop it works for a while
 * (so a host killed under it is killed mid-stop), reports "KEY/NONCE" where KEY names the stop
 * (round and index: unique per stop of its trip) and NONCE is drawn when the stop's work runs,
 * and keeps KEY in its state. The home can then tell a stop run twice (one KEY, two nonces) from a
 * report delivered twice (one KEY and nonce, twice) and from a report lost (a KEY in the state
 * that never came as a report). At the deadline it ends its trip with its keys as the result.
 */
public class SoakAgent extends Agent {

    private static final long serialVersionUID = 1L;

    private final long endAtMillis;
    private final int workMillis;
    private final ArrayList<String> stops = new ArrayList<>();

    /**
     * @param endAtMillis when to end the trip (wall clock, ms since the epoch: every JVM of the test is on this machine)
     * @param workMillis  how long each stop works
     */
    public SoakAgent(long endAtMillis, int workMillis) {
        this.endAtMillis = endAtMillis;
        this.workMillis = workMillis;
    }

    @Override
    public void run() {
        Itinerary it = context().itinerary();
        String key = it.round() + ":" + it.currentIndex();
        if (workMillis > 0) {
            try {
                Thread.sleep(workMillis); // the stop's work
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
        context().report(key + "/" + Long.toHexString(ThreadLocalRandom.current().nextLong()));
        stops.add(key);
        if (System.currentTimeMillis() >= endAtMillis) {
            // The end of this round is the end of the trip.
            while (it.stops().size() > it.currentIndex() + 1) {
                it.removeStop(it.currentIndex() + 1);
            }
            it.repeat(it.round() + 1);
        }
        context().setResult(new ArrayList<>(stops));
    }
}
