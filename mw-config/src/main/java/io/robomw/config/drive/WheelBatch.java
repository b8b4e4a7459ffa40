package io.robomw.config.drive;

import java.util.List;

/**
 * What a {@link DifferentialDriveBatch} needs of the Platform Layer of a batch of robots on two
 * wheels (the batch's {@link io.robomw.api.spi.RobotPlatform}, as it were): its members' wheel
 * motors, a continuous drive command per member, and their encoders. The Configuration Layer does
 * not depend on the Platform Layer's module; the one who builds the batch (a simulation) adapts
 * its motor batch to this.
 */
public interface WheelBatch {

    /** @return the batch's name, for messages */
    String name();

    /** @return every member's motor ports, in the order speeds are given */
    List<String> ports();

    /** @return how many robots it drives */
    int members();

    /**
     * A member's continuous drive command: its wheel motors turning at these speeds until the
     * next one (or the platform's watchdog); returns at once.
     *
     * @param member the member
     * @param left   the left wheel motor's speed, degrees per second, as the motor turns
     * @param right  the right wheel motor's speed
     */
    void refresh(int member, double left, double right);

    /**
     * @param member the member
     * @param motor  0 for its left wheel motor, 1 for its right
     * @return the motor's encoder now, degrees
     */
    double degrees(int member, int motor);
}
