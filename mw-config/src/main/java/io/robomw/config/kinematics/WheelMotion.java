package io.robomw.config.kinematics;

/**
 * What the two wheel motors of a differential drive must do for one motion, in motor terms.
 *
 * @param leftDegrees            signed rotation of the left motor, degrees
 * @param rightDegrees           signed rotation of the right motor, degrees
 * @param leftDegreesPerSecond   speed magnitude of the left motor
 * @param rightDegreesPerSecond  speed magnitude of the right motor
 */
public record WheelMotion(double leftDegrees, double rightDegrees, double leftDegreesPerSecond, double rightDegreesPerSecond) {
}
