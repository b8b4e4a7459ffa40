package io.robomw.sim.legged;

import java.util.Map;
import java.util.Set;

/**
 * The sensor devices of a Sony Aibo ERS-7 as its URBI server names them, and what the emulated dog
 * reports for a distance sensor its robot file gives no sensor for (nothing in range: the top of
 * the device's range).
 *
 * <table>
 *   <caption>sensor devices</caption>
 *   <tr><th>device</th><th>value</th></tr>
 *   <tr><td>{@code distanceNear}</td><td>head, millimetres, 50 … 500</td></tr>
 *   <tr><td>{@code distanceFar}</td><td>head, millimetres, 200 … 1500</td></tr>
 *   <tr><td>{@code distanceChest}</td><td>chest, millimetres, 100 … 900</td></tr>
 *   <tr><td>{@code accelX}, {@code accelY}, {@code accelZ}</td><td>m/s², x forwards, y left, z up (9.81 standing still)</td></tr>
 *   <tr><td>{@code pawLF}, {@code pawLH}, {@code pawRF}, {@code pawRH}</td><td>1 when that paw touches something</td></tr>
 *   <tr><td>{@code headSensor}, {@code chinSensor}, {@code backSensorF/M/R}</td><td>1 when touched; nobody pets a simulated dog, so 0</td></tr>
 * </table>
 */
public final class AiboDevices {

    private AiboDevices() {
    }

    /** Every sensor device. */
    public static final Set<String> SENSORS = Set.of("distanceNear", "distanceFar", "distanceChest", "accelX", "accelY", "accelZ",
            "pawLF", "pawLH", "pawRF", "pawRH", "headSensor", "chinSensor", "backSensorF", "backSensorM", "backSensorR");

    /** The distance devices and the farthest each reports, millimetres. */
    public static final Map<String, Double> DISTANCE_MAX_MM = Map.of("distanceNear", 500.0, "distanceFar", 1500.0, "distanceChest", 900.0);

    /** The distance devices mounted in the head, which turn with it. */
    public static final Set<String> HEAD_DISTANCE = Set.of("distanceNear", "distanceFar");
}
