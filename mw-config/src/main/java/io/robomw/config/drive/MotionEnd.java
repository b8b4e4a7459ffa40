package io.robomw.config.drive;

/** How a motion's command ended, as its {@link MotionListener} hears of it. */
public enum MotionEnd {
    /** It did all it was commanded to (the platform completed its command). */
    COMPLETED,
    /**
     * It ended before: a newer command took its motors, the robot was stopped, the command failed
     * or was cancelled, or a continuous one's watchdog expired.
     */
    ENDED_EARLY
}
