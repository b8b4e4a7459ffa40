package io.robomw.console.source;

import io.robomw.console.observe.Observation;
import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;

/** What the console, recordings and Foxglove are told of the harbour: its water, and a copter's altitude as it flies. */
class SimSourceVehicleTest {

    private static final Path HARBOUR = Path.of("../examples/worlds/harbour.yaml");

    @Test
    void theHarboursWaterAndTheCoptersAltitudeAreObserved() {
        List<Observation> seen = new CopyOnWriteArrayList<>();
        try (Simulation sim = Simulation.load(HARBOUR); SimSource source = SimSource.watch(sim, seen::add)) {
            sim.run(Duration.ofMinutes(2), () -> sim.robot("copter").takeOff(2));
            Observation.World world = (Observation.World) seen.get(0);
            assertFalse(world.map().water().isEmpty(), "the harbour's water is on the map");
            assertEquals(2.0, last(seen, "copter").z(), 0.2, "the copter's true pose at 2 m");
            assertEquals(0.0, last(seen, "nxt").z(), 0.0, "a wheeled robot stays at 0");
        }
    }

    private static Observation.RobotPose last(List<Observation> seen, String robot) {
        Observation.RobotPose last = null;
        for (Observation o : seen) {
            if (o instanceof Observation.RobotPose p && p.robot().equals(robot)) {
                last = p;
            }
        }
        assertFalse(last == null, "a pose of " + robot + " was observed");
        return last;
    }
}
