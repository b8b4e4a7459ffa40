package io.robomw.sim.render;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

class ViewTransformTest {

    private static final double EPS = 1e-9;

    /** A 4 × 3 m world in a 440 × 340 px image with 20 px margins: exactly 100 px per metre. */
    private static final ViewTransform ARENA = ViewTransform.fit(0, 0, 4, 3, 440, 340, 20);

    @Test
    void shouldMapWorldCornersInsideMarginsWithYAxisUp() {
        assertEquals(100, ARENA.scale(), EPS);
        assertEquals(20, ARENA.screenX(0), EPS);
        assertEquals(320, ARENA.screenY(0), EPS, "the world's origin is at the bottom left");
        assertEquals(420, ARENA.screenX(4), EPS);
        assertEquals(20, ARENA.screenY(3), EPS, "larger y is higher up the screen");
    }

    @Test
    void shouldCentreWorldAlongAxisWithRoomToSpare() {
        ViewTransform t = ViewTransform.fit(0, 0, 4, 3, 840, 340, 20);
        assertEquals(100, t.scale(), EPS, "the height limits the scale");
        assertEquals(220, t.screenX(0), EPS);
        assertEquals(620, t.screenX(4), EPS);
    }

    @Test
    void shouldFitRectangleThatDoesNotStartAtOrigin() {
        ViewTransform t = ViewTransform.fit(-0.1, -0.1, 4.1, 3.1, 440, 340, 10);
        assertEquals(10, t.screenX(-0.1), EPS);
        assertEquals(330, t.screenY(-0.1), EPS);
        assertEquals(430, t.screenX(4.1), EPS);
    }

    @Test
    void shouldMapScreenPointBackToSameWorldPoint() {
        assertEquals(1.25, ARENA.worldX(ARENA.screenX(1.25)), EPS);
        assertEquals(2.75, ARENA.worldY(ARENA.screenY(2.75)), EPS);
    }

    @Test
    void shouldKeepWorldPointUnderPointerWhenZoomingIn() {
        double px = 137;
        double py = 201;
        double wx = ARENA.worldX(px);
        double wy = ARENA.worldY(py);
        ViewTransform zoomed = ARENA.zoomedAbout(px, py, 2);
        assertEquals(200, zoomed.scale(), EPS);
        assertEquals(px, zoomed.screenX(wx), EPS);
        assertEquals(py, zoomed.screenY(wy), EPS);
    }

    @Test
    void shouldKeepWorldPointUnderPointerWhenZoomingOut() {
        ViewTransform zoomed = ARENA.zoomedAbout(300, 40, 0.5);
        assertEquals(50, zoomed.scale(), EPS);
        assertEquals(ARENA.worldX(300), zoomed.worldX(300), EPS);
        assertEquals(ARENA.worldY(40), zoomed.worldY(40), EPS);
    }

    @Test
    void shouldStopZoomingAtLargestScaleAndStillKeepPointerFixed() {
        double wx = ARENA.worldX(100);
        ViewTransform zoomed = ARENA.zoomedAbout(100, 100, 1e9);
        assertEquals(ViewTransform.MAX_SCALE, zoomed.scale(), EPS);
        assertEquals(100, zoomed.screenX(wx), 1e-6);
    }

    @Test
    void shouldMovePictureByDraggedPixels() {
        ViewTransform moved = ARENA.panned(15, -30);
        assertEquals(ARENA.screenX(1) + 15, moved.screenX(1), EPS);
        assertEquals(ARENA.screenY(1) - 30, moved.screenY(1), EPS);
        assertEquals(ARENA.scale(), moved.scale(), EPS);
    }

    @Test
    void shouldRejectEmptyWorldRectangle() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> ViewTransform.fit(0, 0, 0, 3, 400, 300, 10));
        assertEquals("the world rectangle must not be empty, got x 0.0..0.0, y 0.0..3.0", e.getMessage());
    }

    @Test
    void shouldRejectMarginsThatLeaveNoRoom() {
        assertThrows(IllegalArgumentException.class, () -> ViewTransform.fit(0, 0, 4, 3, 40, 300, 20));
    }

    @Test
    void shouldRejectNonPositiveZoomFactor() {
        assertThrows(IllegalArgumentException.class, () -> ARENA.zoomedAbout(0, 0, 0));
    }
}
