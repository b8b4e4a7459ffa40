package io.robomw.sim.render;

/**
 * Maps world coordinates (metres, y up, as in a world file) to screen pixels (y down):
 * {@code screenX = originX + scale · x} and {@code screenY = originY − scale · y}. Immutable; pan
 * and zoom return new transforms, so a viewer can hand one to its painter without locking.
 *
 * @param scale   pixels per metre, between {@link #MIN_SCALE} and {@link #MAX_SCALE}
 * @param originX screen x of the world's origin, pixels
 * @param originY screen y of the world's origin, pixels
 */
public record ViewTransform(double scale, double originX, double originY) {

    /** The smallest scale, pixels per metre (a 100 km arena fits in 100 pixels). */
    public static final double MIN_SCALE = 1e-3;
    /** The largest scale, pixels per metre (a millimetre is 100 pixels). */
    public static final double MAX_SCALE = 1e5;

    /** Checks the scale and the origin. */
    public ViewTransform {
        if (!(scale >= MIN_SCALE && scale <= MAX_SCALE)) {
            throw new IllegalArgumentException("scale must be between " + MIN_SCALE + " and " + MAX_SCALE + " pixels per metre, got " + scale);
        }
        if (!Double.isFinite(originX) || !Double.isFinite(originY)) {
            throw new IllegalArgumentException("origin must be finite, got (" + originX + ", " + originY + ")");
        }
    }

    /**
     * The transform that shows a world rectangle as large as possible, centred, inside an image.
     *
     * @param minX     left edge of what must be seen, metres
     * @param minY     bottom edge, metres
     * @param maxX     right edge, metres
     * @param maxY     top edge, metres
     * @param widthPx  image width, pixels
     * @param heightPx image height, pixels
     * @param marginPx free pixels to keep on every side
     * @return the transform
     * @throws IllegalArgumentException if the rectangle is empty or the margins leave no room
     */
    public static ViewTransform fit(double minX, double minY, double maxX, double maxY, int widthPx, int heightPx, int marginPx) {
        if (!(maxX > minX && maxY > minY)) {
            throw new IllegalArgumentException("the world rectangle must not be empty, got x " + minX + ".." + maxX + ", y " + minY + ".." + maxY);
        }
        double roomX = widthPx - 2.0 * marginPx;
        double roomY = heightPx - 2.0 * marginPx;
        if (roomX <= 0 || roomY <= 0) {
            throw new IllegalArgumentException("a " + widthPx + " × " + heightPx + " px image with " + marginPx + " px margins has no room left to draw in");
        }
        double scale = clampScale(Math.min(roomX / (maxX - minX), roomY / (maxY - minY)));
        double originX = widthPx / 2.0 - scale * (minX + maxX) / 2;
        double originY = heightPx / 2.0 + scale * (minY + maxY) / 2;
        return new ViewTransform(scale, originX, originY);
    }

    /**
     * @param x world x, metres
     * @return screen x, pixels
     */
    public double screenX(double x) {
        return originX + scale * x;
    }

    /**
     * @param y world y, metres
     * @return screen y, pixels (down the screen)
     */
    public double screenY(double y) {
        return originY - scale * y;
    }

    /**
     * @param screenX screen x, pixels
     * @return world x, metres
     */
    public double worldX(double screenX) {
        return (screenX - originX) / scale;
    }

    /**
     * @param screenY screen y, pixels
     * @return world y, metres
     */
    public double worldY(double screenY) {
        return (originY - screenY) / scale;
    }

    /**
     * Zooms keeping one screen point over the same world point (the mouse pointer, for a wheel).
     * The scale stays between {@link #MIN_SCALE} and {@link #MAX_SCALE}.
     *
     * @param screenX the fixed point's screen x, pixels
     * @param screenY the fixed point's screen y, pixels
     * @param factor  how much larger things get; above 1 zooms in
     * @return the zoomed transform
     */
    public ViewTransform zoomedAbout(double screenX, double screenY, double factor) {
        if (!(factor > 0) || Double.isInfinite(factor)) {
            throw new IllegalArgumentException("zoom factor must be a finite number > 0, got " + factor);
        }
        double newScale = clampScale(scale * factor);
        double applied = newScale / scale;
        return new ViewTransform(newScale, screenX - applied * (screenX - originX), screenY - applied * (screenY - originY));
    }

    /**
     * @param dxPx how far the picture moves right, pixels
     * @param dyPx how far the picture moves down, pixels
     * @return the moved transform (a mouse drag of that many pixels)
     */
    public ViewTransform panned(double dxPx, double dyPx) {
        return new ViewTransform(scale, originX + dxPx, originY + dyPx);
    }

    private static double clampScale(double s) {
        return Math.max(MIN_SCALE, Math.min(MAX_SCALE, s));
    }
}
