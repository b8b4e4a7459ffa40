package io.robomw.platform;

import java.time.Duration;
import java.util.function.BooleanSupplier;

import static org.junit.jupiter.api.Assertions.fail;

/** The Platform Layer tests' one wait: a condition checked every millisecond until a deadline. */
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
            if (System.nanoTime() > deadline) {
                fail("not true within " + within.toMillis() + " ms: " + what);
            }
            java.util.concurrent.locks.LockSupport.parkNanos(1_000_000);
        }
    }
}
