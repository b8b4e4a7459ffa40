package io.robomw.platform.ft;

/**
 * What fischertechnik drivers and emulators share about motors: the ports M1..M4, and the speed a
 * motor turns at full power, which both the drivers (to turn a wanted speed into a duty cycle or a
 * PWM value) and the emulators (to turn them back into motion) use.
 */
public final class FtMotors {

    /** Motor speed at full power, degrees per second of the motor shaft (about 0.30 m/s on 56 mm wheels). */
    public static final double DEGREES_PER_SECOND_AT_FULL_POWER = 620;

    private FtMotors() {
    }

    /**
     * @param port a motor port name
     * @param count how many motor outputs the controller has
     * @return its index: M1 = 0 ... M4 = 3
     * @throws IllegalArgumentException if the controller has no such output
     */
    public static int index(String port, int count) {
        if (port.length() == 2 && port.charAt(0) == 'M' && port.charAt(1) >= '1' && port.charAt(1) < '1' + count) {
            return port.charAt(1) - '1';
        }
        throw new IllegalArgumentException("fischertechnik motor ports are M1 to M" + count + ", not '" + port + "'");
    }

    /**
     * @param degreesPerSecond a wanted motor speed
     * @return the fraction of full power it needs, −1..1
     */
    public static double duty(double degreesPerSecond) {
        return Math.max(-1, Math.min(1, degreesPerSecond / DEGREES_PER_SECOND_AT_FULL_POWER));
    }
}
