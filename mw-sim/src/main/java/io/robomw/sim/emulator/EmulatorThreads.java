package io.robomw.sim.emulator;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.IdleStrategy;

import java.util.concurrent.locks.LockSupport;

/**
 * What the emulators' threads share: how their {@link io.robomw.api.spi.OwnerThread}s wait
 * between rounds, and how a thread that serves one peer and ends with it (an Aibo client's reader
 * or writer) hands its last failure to the {@link FailurePolicy}.
 */
public final class EmulatorThreads {

    /** How long a round that did nothing, or failed, is followed by a wait, nanoseconds. */
    private static final long BACK_OFF_NANOS = 10_000_000;

    /**
     * The emulators' idle strategy: no wait after a round that did something (each round waits on
     * its input itself, with a deadline), and 10 ms after one that did nothing or failed, so a
     * failure repeated every round is reported at that pace instead of spinning.
     */
    public static final IdleStrategy BACK_OFF = work -> {
        if (work <= 0) {
            LockSupport.parkNanos(BACK_OFF_NANOS);
        }
    };

    private EmulatorThreads() {
    }

    /**
     * Reports what ended a thread that serves one peer (the peer is then dropped): survived if
     * the process can go on after it, else a death.
     *
     * @param failures the policy
     * @param role     the thread's name
     * @param failure  what it caught
     */
    public static void ended(FailurePolicy failures, String role, Throwable failure) {
        if (FailurePolicy.survivable(failure)) {
            failures.survived(role, failure);
        } else {
            failures.died(role, failure);
        }
    }
}
