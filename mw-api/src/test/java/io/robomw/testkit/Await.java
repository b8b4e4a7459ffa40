package io.robomw.testkit;

import org.awaitility.Awaitility;
import org.awaitility.core.ConditionTimeoutException;

import java.time.Duration;
import java.util.function.BooleanSupplier;
import java.util.function.Supplier;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * The tests' one wait: a condition with a deadline, through Awaitility (checked on the calling
 * thread every millisecond or so, never a sleep of a guessed length). A test that waits for
 * something calls this, or waits on a latch or a future the code offers, with a deadline.
 */
public final class Await {

    private Await() {
    }

    /**
     * Waits until a condition holds.
     *
     * @param what      the condition, for the failure message
     * @param within    the deadline; generous (seconds), since a loaded machine is slow, not wrong
     * @param condition the condition
     */
    public static void until(String what, Duration within, BooleanSupplier condition) {
        until(what, within, condition, () -> "");
    }

    /**
     * Waits until a condition holds, and says what was last seen if it does not.
     *
     * @param what      the condition, for the failure message
     * @param within    the deadline
     * @param condition the condition
     * @param state     what to add to the failure message (the last state seen)
     */
    public static void until(String what, Duration within, BooleanSupplier condition, Supplier<String> state) {
        try {
            Awaitility.await(what).atMost(within).pollInSameThread().pollDelay(Duration.ZERO)
                    .pollInterval(Duration.ofMillis(1)).until(condition::getAsBoolean);
        } catch (ConditionTimeoutException e) {
            String seen = state.get();
            fail("not true within " + within.toMillis() + " ms: " + what + (seen.isEmpty() ? "" : " " + seen));
        }
    }
}
