package io.robomw.console.observe;

/**
 * Takes observations: the console's view, a recorder. Called from the sources' threads (several at
 * once), so implementations are thread-safe, quick, and never throw back into a source: a source
 * that owns a robot or a world must not stall or die because a browser or a disk is slow.
 */
@FunctionalInterface
public interface Observer {

    /** @param observation what was seen */
    void observe(Observation observation);

    /**
     * @param observers observers to tell, in order
     * @return one observer telling them all; one that throws is logged and the others still hear
     */
    static Observer all(Observer... observers) {
        Observer[] copy = observers.clone();
        return o -> {
            for (Observer x : copy) {
                try {
                    x.observe(o);
                } catch (RuntimeException e) {
                    org.slf4j.LoggerFactory.getLogger(Observer.class).warn("observer {} failed on {}: {}", x, o.getClass().getSimpleName(), e.toString());
                }
            }
        };
    }
}
