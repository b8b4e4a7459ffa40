package io.robomw.api;

/** Where a sensor sits on the robot, as {@link Perception#getValue} names it. */
public enum Position {
    /** Facing forwards. */
    FRONT,
    /** Facing backwards. */
    BACK,
    /** Facing left. */
    LEFT,
    /** Facing right. */
    RIGHT,
    /** Forwards and to the left. */
    FRONT_LEFT,
    /** Forwards and to the right. */
    FRONT_RIGHT,
    /** Backwards and to the left. */
    BACK_LEFT,
    /** Backwards and to the right. */
    BACK_RIGHT,
    /** On top, facing up. */
    TOP,
    /** Underneath, facing the floor (line and floor-colour sensors). */
    BOTTOM,
    /** In the body (gyro, compass). */
    CENTER
}
