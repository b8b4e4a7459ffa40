package io.robomw.config.kinematics;

import io.robomw.config.description.DifferentialDrive;

/**
 * Turns motions of a two-wheeled differential robot (metres, radians) into motor rotations
 * (degrees) and back.
 *
 * <p>Conventions: a positive distance drives forwards; a positive angle turns left
 * (anti-clockwise seen from above). A wheel of diameter {@code d} covers {@code π·d} metres per
 * turn, and its motor turns {@code gearRatio} times per wheel turn, so one metre is
 * {@code 360·gearRatio/(π·d)} motor degrees. On the spot, each wheel runs on a circle of diameter
 * {@code trackWidth}: turning by {@code θ} moves the right wheel {@code θ·trackWidth/2} forwards and
 * the left one as far backwards. A reversed motor gets the opposite sign.
 *
 * <p>Why not model it as leJOS' {@code WheeledChassis} does (holonomic plus a dummy wheel)? With
 * two wheels the closed form is exact, has no matrix to invert, and is what the paper's
 * configuration layer computes; arcs are the general case, and straight lines and turns on the
 * spot are its limits. Immutable and thread-safe.
 */
public final class DifferentialKinematics {

    private final DifferentialDrive drive;
    private final double motorDegreesPerMetre;

    /**
     * @param drive the wheel layout
     */
    public DifferentialKinematics(DifferentialDrive drive) {
        this.drive = drive;
        this.motorDegreesPerMetre = 360.0 * drive.gearRatio() / (Math.PI * drive.wheelDiameter());
    }

    /** @return the wheel layout */
    public DifferentialDrive drive() {
        return drive;
    }

    /**
     * Straight line.
     *
     * @param distance metres, negative backwards
     * @param speed    metres per second, &gt; 0
     * @return the motor motion
     */
    public WheelMotion move(double distance, double speed) {
        return wheels(distance, distance, speed, speed);
    }

    /**
     * Turn on the spot.
     *
     * @param radians positive turns left
     * @param angularSpeed radians per second, &gt; 0
     * @return the motor motion
     */
    public WheelMotion turn(double radians, double angularSpeed) {
        double half = drive.trackWidth() / 2;
        double wheelSpeed = angularSpeed * half;
        return wheels(-radians * half, radians * half, wheelSpeed, wheelSpeed);
    }

    /**
     * Circular arc.
     *
     * @param radius metres from the centre of the circle to the robot's centre; positive centre on
     *               the left; 0 turns on the spot
     * @param angle  radians of arc; positive drives forwards
     * @param speed  metres per second of the robot's centre (for radius 0: of each wheel)
     * @return the motor motion
     */
    public WheelMotion arc(double radius, double angle, double speed) {
        if (radius == 0) {
            return turn(angle, speed / (drive.trackWidth() / 2));
        }
        double half = drive.trackWidth() / 2;
        double heading = angle * Math.signum(radius);
        double centre = Math.abs(radius) * angle;
        double left = centre - heading * half;
        double right = centre + heading * half;
        double scale = speed / Math.abs(radius);
        double leftSpeed = Math.abs(Math.abs(radius) - Math.signum(radius) * half) * scale;
        double rightSpeed = Math.abs(Math.abs(radius) + Math.signum(radius) * half) * scale;
        return wheels(left, right, leftSpeed, rightSpeed);
    }

    /**
     * Continuous velocities.
     *
     * @param linearSpeed  metres per second, negative backwards
     * @param angularSpeed radians per second, positive left
     * @return signed motor speeds, degrees per second, as {@code leftDegreesPerSecond} and
     *         {@code rightDegreesPerSecond} (the degrees fields are 0)
     */
    public WheelMotion velocity(double linearSpeed, double angularSpeed) {
        double half = drive.trackWidth() / 2;
        double left = (linearSpeed - angularSpeed * half) * motorDegreesPerMetre;
        double right = (linearSpeed + angularSpeed * half) * motorDegreesPerMetre;
        return new WheelMotion(0, 0, drive.left().reversed() ? -left : left, drive.right().reversed() ? -right : right);
    }

    /**
     * @param motorDegrees rotation of a wheel motor as the motor reports it
     * @param reversed     whether that motor is mounted reversed
     * @return metres the wheel rolled forwards
     */
    public double wheelMetres(double motorDegrees, boolean reversed) {
        return (reversed ? -motorDegrees : motorDegrees) / motorDegreesPerMetre;
    }

    /** @return motor degrees per metre of wheel travel */
    public double motorDegreesPerMetre() {
        return motorDegreesPerMetre;
    }

    /** @return the fastest a motor may turn, degrees per second, from the description's max speed */
    public double maxMotorDegreesPerSecond() {
        return drive.maxSpeed() * motorDegreesPerMetre;
    }

    private WheelMotion wheels(double leftMetres, double rightMetres, double leftSpeed, double rightSpeed) {
        double l = leftMetres * motorDegreesPerMetre;
        double r = rightMetres * motorDegreesPerMetre;
        return new WheelMotion(drive.left().reversed() ? -l : l, drive.right().reversed() ? -r : r,
                leftSpeed * motorDegreesPerMetre, rightSpeed * motorDegreesPerMetre);
    }
}
