package io.robomw.config.description;

/**
 * A two-wheeled differential drive: two driven wheels on one axle, steering by speed difference.
 *
 * @param wheelDiameter   metres
 * @param trackWidth      metres between the wheels' contact points
 * @param gearRatio       motor turns per wheel turn (1 when the wheel sits on the motor)
 * @param maxSpeed        metres per second at the wheel rim, the fastest a wheel may be asked to go
 * @param encoderTicksPerRevolution encoder ticks per motor turn (360 on LEGO motors); 0 when the
 *                        motors have no encoders
 * @param left            the left wheel's motor
 * @param right           the right wheel's motor
 */
public record DifferentialDrive(double wheelDiameter, double trackWidth, double gearRatio, double maxSpeed,
                                int encoderTicksPerRevolution, Wheel left, Wheel right) implements DriveSpec {

    /** Checks the geometry, naming the value and the rule. */
    public DifferentialDrive {
        requirePositive("wheel_diameter", wheelDiameter);
        requirePositive("track_width", trackWidth);
        requirePositive("gear_ratio", gearRatio);
        requirePositive("max_speed", maxSpeed);
        if (encoderTicksPerRevolution < 0) {
            throw new IllegalArgumentException("encoder_ticks_per_revolution must be >= 0, got " + encoderTicksPerRevolution);
        }
        if (left.port().equals(right.port())) {
            throw new IllegalArgumentException("left and right wheels must be on different ports, both are on " + left.port());
        }
    }

    /** @return {@link DriveKind#DIFFERENTIAL} */
    @Override
    public DriveKind kind() {
        return DriveKind.DIFFERENTIAL;
    }

    private static void requirePositive(String key, double value) {
        if (!(value > 0) || !Double.isFinite(value)) {
            throw new IllegalArgumentException(key + " must be a number > 0, got " + value);
        }
    }

    /**
     * One driven wheel's motor.
     *
     * @param port     the motor port
     * @param reversed whether the motor is mounted so that its forward drives the wheel backwards
     * @param counter  the input port that counts this wheel's encoder pulses, for bricks whose
     *                 motors have no encoder of their own (a fischertechnik impulse wheel on a
     *                 digital input); empty when the motor port has its own encoder
     */
    public record Wheel(String port, boolean reversed, java.util.Optional<String> counter) {

        /**
         * @param port     the motor port
         * @param reversed whether the motor is mounted reversed
         */
        public Wheel(String port, boolean reversed) {
            this(port, reversed, java.util.Optional.empty());
        }
    }
}
