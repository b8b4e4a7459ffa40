package io.robomw.config.drive;

/**
 * One motion a drive commanded, as its {@link MotionListener} hears of it: its velocities as
 * commanded and how long it was commanded for. A drive numbers its motions in the order it
 * starts them, so that a tracker can tell an old motion's late end from the motion under way.
 *
 * @param sequence       the drive's number for it, increasing with every motion it starts
 * @param linearSpeed    metres per second of the robot's centre, signed (negative backwards)
 * @param angularSpeed   radians per second, signed (positive left)
 * @param plannedSeconds how long it takes at those velocities, or
 *                       {@link Double#POSITIVE_INFINITY} for a continuous {@code drive}
 */
public record Movement(long sequence, double linearSpeed, double angularSpeed, double plannedSeconds) {

    /** @return whether it runs until told otherwise (a {@code drive}, refreshed under its watchdog) */
    public boolean continuous() {
        return plannedSeconds == Double.POSITIVE_INFINITY;
    }
}
