package io.robomw.config.description;

/**
 * The robot's body, for the simulator and for collision-aware programs.
 *
 * @param length   metres, front to back
 * @param width    metres, side to side
 * @param mass     kilograms
 * @param friction coefficient of friction against the floor and walls, ≥ 0
 */
public record Body(double length, double width, double mass, double friction) {

    /** A small LEGO-sized robot: 0.20 × 0.15 m, 0.6 kg, friction 0.8. */
    public static final Body DEFAULT = new Body(0.20, 0.15, 0.6, 0.8);
}
