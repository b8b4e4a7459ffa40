package io.robomw.platform;

import java.time.Duration;
import java.util.concurrent.locks.LockSupport;
import java.util.function.BooleanSupplier;

import static org.junit.jupiter.api.Assertions.fail;

/** mw-platform's one wait helper, for tests on the wall clock: a condition with a deadline, checked every millisecond, never a sleep. */
public final class Await {

    private Await() {
    }

    /**
     * @param what      the condition, for the failure message
     * @param within    the deadline
     * @param condition the condition
     */
    public static void until(String what, Duration within, BooleanSupplier condition) {
        long deadline = System.nanoTime() + within.toNanos();
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() - deadline > 0) {
                fail("not true within " + within + ": " + what);
            }
            LockSupport.parkNanos(1_000_000);
        }
    }
}
