package io.robomw.sim.emulator.ev3;

import java.util.List;
import java.util.Optional;

/**
 * The rows of the firmware's {@code typedata.rcf} that the emulator reports: for each device type
 * and mode, the raw, percent and SI ranges. The firmware turns a device's raw reading into percent
 * and SI linearly between these ranges; the emulator goes the other way too, so that its values
 * are quantised as the device's raw data is (the ultrasonic sensor to 0.1 cm, the gyro to 1°).
 */
final class Ev3DeviceModes {

    /**
     * One type and mode.
     *
     * @param type   the device type
     * @param mode   the mode
     * @param rawMin raw value at the low end
     * @param rawMax raw value at the high end
     * @param pctMin percent at the low end
     * @param pctMax percent at the high end
     * @param siMin  SI value at the low end
     * @param siMax  SI value at the high end
     */
    record Row(int type, int mode, double rawMin, double rawMax, double pctMin, double pctMax, double siMin, double siMax) {

        /**
         * @param si a value in the device's SI unit
         * @return the raw reading that gives it, rounded as the device's integer data is
         */
        long rawOf(double si) {
            return Math.round(rawMin + (si - siMin) * (rawMax - rawMin) / (siMax - siMin));
        }

        /**
         * @param raw a raw reading
         * @return its SI value
         */
        double siOf(double raw) {
            return siMin + (raw - rawMin) * (siMax - siMin) / (rawMax - rawMin);
        }

        /**
         * @param raw a raw reading
         * @return its percent value, rounded
         */
        long pctOf(double raw) {
            return Math.round(pctMin + (raw - rawMin) * (pctMax - pctMin) / (rawMax - rawMin));
        }
    }

    private static final List<Row> ROWS = List.of(
            new Row(7, 0, -180, 180, 0, 100, -180, 180),
            new Row(7, 1, -36000, 36000, 0, 100, -100, 100),
            new Row(7, 2, -100, 100, -100, 100, -100, 100),
            new Row(8, 0, -180, 180, 0, 100, -180, 180),
            new Row(8, 1, -36000, 36000, 0, 100, -100, 100),
            new Row(8, 2, -100, 100, -100, 100, -100, 100),
            new Row(16, 0, 1000, 2000, 0, 100, 0, 1),
            new Row(16, 1, 0, 1, 0, 100, 0, 1),
            new Row(29, 0, 0, 100, 0, 100, 0, 100),
            new Row(29, 1, 0, 100, 0, 100, 0, 100),
            new Row(29, 2, 0, 8, 0, 100, 0, 8),
            new Row(30, 0, 0, 2550, 0, 100, 0, 255),
            new Row(30, 1, 0, 1000, 0, 100, 0, 100),
            new Row(30, 2, 0, 1, 0, 100, 0, 1),
            new Row(32, 0, -180, 180, 0, 100, -180, 180),
            new Row(32, 1, -440, 440, 0, 100, -440, 440),
            new Row(33, 0, 0, 100, 0, 100, 0, 100),
            new Row(33, 1, -100, 100, 0, 100, -100, 100),
            new Row(33, 2, 0, 10, 0, 100, 0, 10));

    private Ev3DeviceModes() {
    }

    /**
     * @param type a device type
     * @param mode a mode
     * @return its row, if the emulator knows it
     */
    static Optional<Row> of(int type, int mode) {
        return ROWS.stream().filter(r -> r.type() == type && r.mode() == mode).findFirst();
    }
}
