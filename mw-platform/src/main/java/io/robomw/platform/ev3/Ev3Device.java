package io.robomw.platform.ev3;

import java.util.Optional;

/**
 * EV3 device types that this driver and the emulator know, with their numbers and modes from the
 * firmware's {@code typedata.rcf}. Other type numbers may still be asked for through a sensor's
 * {@code ev3_type} option; the brick decides what they mean.
 */
public enum Ev3Device {
    /** Large motor read as a sensor: mode 0 degrees, 1 rotations, 2 speed %. */
    LARGE_MOTOR(7),
    /** Medium motor read as a sensor: modes as the large motor. */
    MEDIUM_MOTOR(8),
    /** EV3 touch sensor: mode 0 touch (SI 1 pressed, 0 released), 1 bumps. */
    TOUCH(16),
    /** EV3 colour sensor: mode 0 reflected light %, 1 ambient light %, 2 colour number 0..7. */
    COLOR(29),
    /** EV3 ultrasonic sensor: mode 0 distance cm (0..255.0), 1 distance inch, 2 listen. */
    ULTRASONIC(30),
    /** EV3 gyro sensor: mode 0 angle degrees, 1 rate degrees per second. */
    GYRO(32),
    /** EV3 infra-red sensor: mode 0 proximity % (0..100), 1 seek, 2 remote. */
    INFRARED(33),
    /** Nothing connected. */
    NONE(126),
    /** A device the brick cannot identify. */
    ERROR(127);

    /** The mode parameter that keeps a port's current mode. */
    public static final int KEEP_MODE = -1;
    /** The type parameter that keeps a port's current type. */
    public static final int KEEP_TYPE = 0;

    private final int type;

    Ev3Device(int type) {
        this.type = type;
    }

    /** @return its device type number */
    public int type() {
        return type;
    }

    /**
     * @param type a device type number
     * @return the device, if it is one of these
     */
    public static Optional<Ev3Device> of(int type) {
        for (Ev3Device d : values()) {
            if (d.type == type) {
                return Optional.of(d);
            }
        }
        return Optional.empty();
    }
}
