package io.robomw.bench.jade;

import jade.core.Agent;
import jade.core.ContainerID;

import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.LongPredicate;

/**
 * An agent of the many-agents JADE baseline ({@code ManyAgentsBenchmark}): created on its home
 * container, it {@link #doMove}s to a container picked at random among the others, over and over,
 * and at each arrival hands the hop's latency (from just before {@code doMove} to
 * {@link #afterMove()}) to the {@link LongPredicate} of that JVM's system property
 * {@code robomw.bench.many.hop}, which says whether to go on. Once told to stop it goes home and
 * counts itself in {@code robomw.bench.many.home}, then deletes itself.
 *
 * <p>Arguments: the names of every container ({@code String[]}), a seed ({@link Long}). The same
 * as the RoboMW agent of that benchmark carries: the host list, a random state and a departure time.
 */
public final class JadeHopperAgent extends Agent {

    private String[] containers;
    private String home;
    private long seed;
    private long departed;

    @Override
    protected void setup() {
        Object[] args = getArguments();
        containers = (String[]) args[0];
        seed = (Long) args[1] | 1;
        setArguments(null);
        home = here().getName();
        hop(home);
    }

    @Override
    protected void afterMove() {
        long now = System.nanoTime();
        String here = here().getName();
        LongPredicate log = (LongPredicate) System.getProperties().get("robomw.bench.many.hop");
        if (log.test(departed == 0 ? -1 : now - departed)) {
            hop(here);
        } else if (!here.equals(home)) {
            departed = 0;
            doMove(new ContainerID(home, null));
        } else {
            ((AtomicInteger) System.getProperties().get("robomw.bench.many.home")).incrementAndGet();
            doDelete();
        }
    }

    private void hop(String here) {
        long wait = io.robomw.bench.many.HopLog.waitNanos(seed);
        if (wait > 0) {
            // paced: waits at this stop (on its own thread, as JADE runs agents) before it leaves
            try {
                java.util.concurrent.TimeUnit.NANOSECONDS.sleep(wait);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
        String next;
        do {
            seed ^= seed << 13;
            seed ^= seed >>> 7;
            seed ^= seed << 17;
            next = containers[(int) Math.floorMod(seed, (long) containers.length)];
        } while (next.equals(here));
        departed = System.nanoTime();
        doMove(new ContainerID(next, null));
    }
}
