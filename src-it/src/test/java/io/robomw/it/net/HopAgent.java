package io.robomw.it.net;

import io.robomw.api.Agent;
import io.robomw.api.Itinerary;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ThreadLocalRandom;

/**
 * The network scenarios' agent. At each stop it works a while, reports {@code KEY/NONCE} home
 * (KEY names the stop: the host and the stop's place in the trip, unique within the trip; NONCE is
 * drawn when the stop's work runs) and keeps KEY; its result is the list of its keys. So the home
 * tells a stop run twice (one KEY, two nonces), a report delivered twice (one KEY/NONCE twice) and
 * a report lost (a KEY of the result that never came as a report). A clone sent to one host adds
 * the stops of its tour there, at its first stop.
 */
public class HopAgent extends Agent {

    private static final long serialVersionUID = 1L;

    private final int workMillis;
    private final ArrayList<String> tour;
    private final ArrayList<String> keys = new ArrayList<>();
    private boolean toured;

    /**
     * @param workMillis how long each stop works
     * @param tour       stops a clone adds after its first, or empty
     */
    public HopAgent(int workMillis, List<String> tour) {
        this.workMillis = workMillis;
        this.tour = new ArrayList<>(tour);
    }

    @Override
    public void run() {
        Itinerary it = context().itinerary();
        if (!toured) {
            tour.forEach(it::addStop);
            toured = true;
        }
        String key = context().hostName() + "#" + it.round() + ":" + it.currentIndex();
        try {
            Thread.sleep(workMillis); // the stop's work
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return;
        }
        context().report(key + "/" + Long.toHexString(ThreadLocalRandom.current().nextLong()));
        keys.add(key);
        context().setResult(new ArrayList<>(keys));
    }
}
