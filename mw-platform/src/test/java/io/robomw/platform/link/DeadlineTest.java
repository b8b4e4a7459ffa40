package io.robomw.platform.link;

import org.junit.jupiter.api.Test;

import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class DeadlineTest {

    @Test
    void shouldRejectNegativeTimeoutNamingIt() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> Deadline.after(Duration.ofMillis(-5)));
        assertEquals("timeout must not be negative, timeout=PT-0.005S", e.getMessage());
    }

    @Test
    void shouldBeExpiredAtOnceForZeroTimeout() {
        Deadline deadline = Deadline.after(Duration.ZERO);
        assertTrue(deadline.expired());
        assertEquals(0, deadline.remainingMillisRoundedUp());
    }

    @Test
    void shouldRoundMillisUpSoWaitsNeverEndEarly() {
        assertEquals(0, Deadline.millisRoundedUp(0));
        assertEquals(1, Deadline.millisRoundedUp(1));
        assertEquals(1, Deadline.millisRoundedUp(1_000_000));
        assertEquals(2, Deadline.millisRoundedUp(1_000_001));
    }

    @Test
    void shouldNotOverflowForHugeTimeouts() {
        Deadline deadline = Deadline.after(Duration.ofDays(365L * 1000));
        assertFalse(deadline.expired());
        assertEquals(Integer.MAX_VALUE, deadline.remainingMillisRoundedUp());
    }
}
