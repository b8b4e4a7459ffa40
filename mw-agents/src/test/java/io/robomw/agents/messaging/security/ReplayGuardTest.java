package io.robomw.agents.messaging.security;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

class ReplayGuardTest {

    private final ReplayGuard guard = new ReplayGuard();

    @Test
    void shouldAcceptAFirstFrameAndRejectItsReplay() {
        assertTrue(guard.accept(1, 10));
        assertFalse(guard.accept(1, 10));
    }

    @Test
    void shouldAcceptOutOfOrderFramesWithinTheWindow() {
        assertTrue(guard.accept(1, 100));
        assertTrue(guard.accept(1, 98));
        assertTrue(guard.accept(1, 99));
        assertFalse(guard.accept(1, 98));
    }

    @Test
    void shouldRejectFramesBelowTheWindow() {
        assertTrue(guard.accept(1, 10_000));
        assertFalse(guard.accept(1, 10_000 - ReplayGuard.WINDOW));
    }

    @Test
    void shouldForgetNumbersThatTheWindowMovedPast() {
        assertTrue(guard.accept(1, 5));
        assertTrue(guard.accept(1, 5 + ReplayGuard.WINDOW));
        assertTrue(guard.accept(1, 5 + ReplayGuard.WINDOW + 1));
        assertFalse(guard.accept(1, 5 + ReplayGuard.WINDOW));
    }

    @Test
    void shouldKeepSourcesApart() {
        assertTrue(guard.accept(1, 7));
        assertTrue(guard.accept(2, 7));
    }

    @Test
    void shouldJudgeFreshnessBothWays() {
        assertTrue(ReplayGuard.fresh(1_000, 1_500, 500));
        assertFalse(ReplayGuard.fresh(1_000, 1_501, 500));
        assertFalse(ReplayGuard.fresh(2_001, 1_500, 500));
    }

    @Test
    void seenTellsAReplayWithoutRecordingAnything() {
        assertFalse(guard.seen(1, 5), "nothing from the source yet");
        assertTrue(guard.accept(1, 5));
        assertTrue(guard.seen(1, 5));
        assertFalse(guard.seen(1, 4), "below the highest, in the window, not seen");
        assertFalse(guard.seen(1, 6));
        assertTrue(guard.accept(1, 4), "seen did not record 4");
        assertTrue(guard.accept(1, 6 + ReplayGuard.WINDOW));
        assertTrue(guard.seen(1, 6), "below the window");
        assertFalse(guard.seen(2, 5), "another source");
    }
}
