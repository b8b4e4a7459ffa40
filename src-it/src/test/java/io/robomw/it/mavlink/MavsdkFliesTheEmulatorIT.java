package io.robomw.it.mavlink;

import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An independent client accepts the MAVLink emulator: MAVSDK (PyPI mavsdk 4.1.0) flies
 * {@code mw emulate mavlink}, in its own JVM through the mw launcher's class path, as it flies
 * ArduPilot SITL or PX4 SITL: the emulator sends to MAVSDK's port (SITL's --out), MAVSDK arms,
 * takes off, flies offboard by position and by body velocity and lands, in both dialects; a boat
 * sails by velocity and position and refuses to take off (mavsdk_flight.py).
 */
class MavsdkFliesTheEmulatorIT {

    private static final Duration WAIT = Duration.ofSeconds(60);
    private static final Duration FLIGHT = Duration.ofMinutes(3);

    private static List<String> fly(String robot, String autopilot, String kind) throws Exception {
        int port = VehiclePython.freeUdpPort();
        try (MwProcess vehicle = MwProcess.start("mavsdk-" + robot + "-" + autopilot, "emulate", "mavlink", "--world", "examples/worlds/harbour.yaml",
                "--robot", robot, "--autopilot", autopilot, "--gcs", "udp://127.0.0.1:" + port)) {
            vehicle.await("sending to udp://127.0.0.1:" + port, WAIT);
            try (VehiclePython mavsdk = VehiclePython.start("mavsdk-flight-" + robot + "-" + autopilot, "mavsdk_flight.py",
                    "udpin://127.0.0.1:" + port, kind)) {
                return mavsdk.expectDone(FLIGHT);
            }
        }
    }

    @Test
    void mavsdkFliesAnEmulatedArduCopter() throws Exception {
        List<String> ok = fly("copter", "ardupilot", "copter");
        assertTrue(ok.stream().anyMatch(l -> l.startsWith("OK offboard-position")), String.valueOf(ok));
        assertTrue(ok.stream().anyMatch(l -> l.startsWith("OK landed")), String.valueOf(ok));
    }

    @Test
    void mavsdkFliesAnEmulatedPx4Copter() throws Exception {
        List<String> ok = fly("copter-px4", "px4", "copter");
        assertTrue(ok.stream().anyMatch(l -> l.startsWith("OK offboard-velocity")), String.valueOf(ok));
        assertTrue(ok.stream().anyMatch(l -> l.startsWith("OK landed")), String.valueOf(ok));
    }

    @Test
    void mavsdkSailsAnEmulatedBoatWhichCannotTakeOff() throws Exception {
        List<String> ok = fly("boat", "ardupilot", "boat");
        assertTrue(ok.stream().anyMatch(l -> l.startsWith("OK offboard-position")), String.valueOf(ok));
        assertTrue(ok.stream().anyMatch(l -> l.startsWith("OK no-takeoff")), String.valueOf(ok));
    }
}
