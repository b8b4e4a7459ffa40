package io.robomw.bench.jade;

import java.time.Duration;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * Collects the round trips of the current measurement in the home container's JVM (static, so
 * nothing of it travels with the agent). One measurement at a time.
 */
final class JadeRoundTripLog {

    private static volatile Run current;

    private JadeRoundTripLog() {
    }

    /** Starts a measurement of {@code warmup} unrecorded and {@code iterations} recorded round trips of the agent {@code agent}. */
    static Run begin(String agent, int payloadBytes, int warmup, int iterations) {
        Run run = new Run(agent, payloadBytes, warmup, iterations);
        current = run;
        return run;
    }

    /**
     * Called by the agent on its home container after each round trip.
     *
     * @return whether the agent should go round again (an agent left over from an abandoned
     *         measurement is told to stop)
     */
    static boolean record(String agent, long nanos, int payloadBytes) {
        Run run = current;
        return run != null && run.agent.equals(agent) && run.record(nanos, payloadBytes);
    }

    /** One measurement. */
    static final class Run {
        private final String agent;
        private final int payloadBytes;
        private final int warmup;
        private final long[] nanos;
        private final CountDownLatch finished = new CountDownLatch(1);
        private volatile int done;
        private volatile String failure;

        private Run(String agent, int payloadBytes, int warmup, int iterations) {
            this.agent = agent;
            this.payloadBytes = payloadBytes;
            this.warmup = warmup;
            this.nanos = new long[iterations];
        }

        /** Called on the agent's thread, one round trip after the other (each on a fresh thread). */
        private boolean record(long roundTrip, int carried) {
            if (carried != payloadBytes) {
                failure = "agent carried " + carried + " bytes, expected " + payloadBytes;
                finished.countDown();
                return false;
            }
            int i = done;
            if (i >= warmup + nanos.length) {
                return false;
            }
            if (i >= warmup) {
                nanos[i - warmup] = roundTrip;
            }
            done = i + 1;
            if (i + 1 == warmup + nanos.length) {
                finished.countDown();
                return false;
            }
            return true;
        }

        /**
         * Waits for the last round trip.
         *
         * @param idle how long a single round trip may take before the measurement is given up
         * @return the recorded round trips, nanoseconds
         */
        long[] await(Duration idle) throws InterruptedException, TimeoutException {
            int seen = 0;
            while (!finished.await(idle.toNanos(), TimeUnit.NANOSECONDS)) {
                int now = done;
                if (now == seen) {
                    throw new TimeoutException("no round trip completed within " + idle + " (" + now + " of " + (warmup + nanos.length) + " done)");
                }
                seen = now;
            }
            if (failure != null) {
                throw new IllegalStateException(failure);
            }
            return nanos;
        }
    }
}
