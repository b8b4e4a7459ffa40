package io.robomw.it;

import java.time.Duration;
import java.util.concurrent.locks.LockSupport;
import java.util.function.BooleanSupplier;
import java.util.function.Supplier;

import static org.junit.jupiter.api.Assertions.fail;

/** Waits for a condition with a deadline, checking it every few milliseconds (the integration tests' one waiting helper). */
public final class Await {

    private Await() {
    }

    /**
     * @param what      the condition, for the failure message
     * @param within    the deadline
     * @param condition the condition
     */
    public static void until(String what, Duration within, BooleanSupplier condition) {
        until(what, within, condition, () -> "");
    }

    /**
     * @param what      the condition, for the failure message
     * @param within    the deadline
     * @param condition the condition
     * @param state     what to add to the failure message (the last state seen)
     */
    public static void until(String what, Duration within, BooleanSupplier condition, Supplier<String> state) {
        long deadline = System.nanoTime() + within.toNanos();
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() > deadline) {
                fail("not true within " + within + ": " + what + " " + state.get());
            }
            LockSupport.parkNanos(5_000_000);
        }
    }
}
