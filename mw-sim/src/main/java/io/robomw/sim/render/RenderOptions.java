package io.robomw.sim.render;

/**
 * What a picture of a world shows and how large it is. Immutable; the {@code with...} methods
 * return changed copies. Shared by the PNG renderer and the viewer.
 *
 * @param widthPx          image width, pixels ({@value #MIN_SIZE_PX} to {@value #MAX_SIZE_PX})
 * @param heightPx         image height, pixels, or {@link #FIT_HEIGHT} to follow the arena's
 *                         aspect ratio (the viewer ignores both: its window has a size)
 * @param marginPx         free pixels around the arena
 * @param showRays         whether range sensors are drawn as rays to their latest reading
 * @param showTrajectories whether each robot's path is drawn
 * @param labelLimit       robots are labelled with their names only when there are at most this many
 */
public record RenderOptions(int widthPx, int heightPx, int marginPx, boolean showRays, boolean showTrajectories, int labelLimit) {

    /** {@link #heightPx} value that makes the image as high as the arena's aspect ratio needs. */
    public static final int FIT_HEIGHT = 0;
    /** Smallest image side, pixels. */
    public static final int MIN_SIZE_PX = 32;
    /** Largest image side, pixels. */
    public static final int MAX_SIZE_PX = 16_384;

    /** 1000 px wide, height from the arena, 24 px margins, paths drawn, no rays, labels up to 20 robots. */
    public static final RenderOptions DEFAULT = new RenderOptions(1000, FIT_HEIGHT, 24, false, true, 20);

    /** Checks the sizes. */
    public RenderOptions {
        if (widthPx < MIN_SIZE_PX || widthPx > MAX_SIZE_PX) {
            throw new IllegalArgumentException("image width must be " + MIN_SIZE_PX + " to " + MAX_SIZE_PX + " px, got " + widthPx);
        }
        if (heightPx != FIT_HEIGHT && (heightPx < MIN_SIZE_PX || heightPx > MAX_SIZE_PX)) {
            throw new IllegalArgumentException("image height must be " + MIN_SIZE_PX + " to " + MAX_SIZE_PX + " px (or FIT_HEIGHT), got " + heightPx);
        }
        if (marginPx < 0 || 2 * marginPx >= Math.min(widthPx, heightPx == FIT_HEIGHT ? widthPx : heightPx)) {
            throw new IllegalArgumentException("margin must be >= 0 px and leave room to draw in a " + widthPx + " px wide image, got " + marginPx);
        }
        if (labelLimit < 0) {
            throw new IllegalArgumentException("label limit must be >= 0, got " + labelLimit);
        }
    }

    /**
     * @param width  image width, pixels
     * @param height image height, pixels, or {@link #FIT_HEIGHT}
     * @return a copy of this size
     */
    public RenderOptions withSize(int width, int height) {
        return new RenderOptions(width, height, marginPx, showRays, showTrajectories, labelLimit);
    }

    /**
     * @param rays whether range sensors are drawn
     * @return a copy with that setting
     */
    public RenderOptions withRays(boolean rays) {
        return new RenderOptions(widthPx, heightPx, marginPx, rays, showTrajectories, labelLimit);
    }

    /**
     * @param trajectories whether paths are drawn
     * @return a copy with that setting
     */
    public RenderOptions withTrajectories(boolean trajectories) {
        return new RenderOptions(widthPx, heightPx, marginPx, showRays, trajectories, labelLimit);
    }

    /**
     * @param limit label robots only when there are at most this many (0: never)
     * @return a copy with that setting
     */
    public RenderOptions withLabelLimit(int limit) {
        return new RenderOptions(widthPx, heightPx, marginPx, showRays, showTrajectories, limit);
    }
}
