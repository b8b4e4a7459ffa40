package io.robomw.console.rosbridge.protocol;

import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.Optional;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Fragments add up to their message in any order, within the limits. */
class DefragmenterTest {

    private static final Limits SMALL = new Limits(1024, 1, 1, 1, 1, 1, 1024, 16, 2, Duration.ofSeconds(10), Duration.ofSeconds(1));

    @Test
    void fragmentsInAnyOrderMakeTheMessage() {
        Defragmenter d = new Defragmenter(SMALL);
        assertTrue(d.add("m", "c", 2, 3, 0).isEmpty());
        assertTrue(d.add("m", "a", 0, 3, 0).isEmpty());
        assertEquals(Optional.of("abc"), d.add("m", "b", 1, 3, 0));
        assertEquals(0, d.pending());
    }

    @Test
    void aFragmentOutsideItsMessageIsRefused() {
        Defragmenter d = new Defragmenter(SMALL);
        assertThrows(IllegalArgumentException.class, () -> d.add("m", "a", 3, 3, 0));
        assertThrows(IllegalArgumentException.class, () -> d.add("m", "a", 0, 0, 0));
        d.add("m", "a", 0, 3, 0);
        assertThrows(IllegalArgumentException.class, () -> d.add("m", "b", 1, 4, 0), "a different total drops the message");
        assertEquals(0, d.pending());
    }

    @Test
    void aClientMaySendOnlySoManyMessagesInPiecesAndSoMuchInAll() {
        Defragmenter d = new Defragmenter(SMALL);
        d.add("1", "a", 0, 2, 0);
        d.add("2", "a", 0, 2, 0);
        assertThrows(IllegalArgumentException.class, () -> d.add("3", "a", 0, 2, 0));
        Defragmenter big = new Defragmenter(SMALL);
        big.add("b", "x".repeat(1000), 0, 2, 0);
        assertThrows(IllegalArgumentException.class, () -> big.add("b", "x".repeat(100), 1, 2, 0));
        assertEquals(0, big.pending());
    }

    @Test
    void aMessageNotCompleteInTimeIsForgotten() {
        Defragmenter d = new Defragmenter(SMALL);
        d.add("old", "a", 0, 2, 0);
        d.add("new", "a", 0, 2, Duration.ofSeconds(11).toNanos());
        assertEquals(1, d.pending());
        assertTrue(d.add("old", "b", 1, 2, Duration.ofSeconds(11).toNanos()).isEmpty(), "its first part is gone");
    }
}
