package io.robomw.api.spi;

import java.util.Objects;
import java.util.Optional;

/**
 * One motor as the platform sees it: what a driver needs from the robot's description about a
 * motor, as {@link SensorChannel} is for a sensor. Drivers read it from
 * {@link PlatformConfig#motors()}; they never see the description itself.
 *
 * @param port                      the motor port, as the platform names it ({@code "B"}, {@code "M1"})
 * @param role                      what the motor drives
 * @param encoderTicksPerRevolution encoder pulses per motor turn that the description gives (for a
 *                                  wheel, {@code drive.encoder_ticks_per_revolution}); 0 when it
 *                                  gives none: the motor has no encoder, or a brick whose motors
 *                                  carry their own encoders knows their resolution itself
 * @param counter                   the input that counts this motor's pulses, for bricks whose
 *                                  motors have no encoder of their own (a fischertechnik impulse
 *                                  wheel on a digital input); empty when the motor port counts
 *                                  itself
 */
public record MotorChannel(String port, Role role, int encoderTicksPerRevolution, Optional<String> counter) {

    /** What a motor drives. */
    public enum Role {
        /** The left wheel of a differential drive. */
        LEFT_WHEEL,
        /** The right wheel of a differential drive. */
        RIGHT_WHEEL,
        /** An extra actuator (a gripper, an arm) with named actions. */
        ACTUATOR;

        /** @return whether this is one of the drive's wheels */
        public boolean wheel() {
            return this != ACTUATOR;
        }
    }

    /** Checks the values. */
    public MotorChannel {
        Objects.requireNonNull(port, "port");
        Objects.requireNonNull(role, "role");
        Objects.requireNonNull(counter, "counter");
        if (encoderTicksPerRevolution < 0) {
            throw new IllegalArgumentException("motor " + port + ": encoderTicksPerRevolution must be >= 0, got " + encoderTicksPerRevolution);
        }
    }

    /**
     * @param port a motor port
     * @return an actuator motor the description says nothing more about
     */
    public static MotorChannel actuator(String port) {
        return new MotorChannel(port, Role.ACTUATOR, 0, Optional.empty());
    }
}
