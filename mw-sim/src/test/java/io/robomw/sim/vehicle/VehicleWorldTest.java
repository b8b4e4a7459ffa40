package io.robomw.sim.vehicle;

import io.robomw.sim.SimRobot;
import io.robomw.sim.Simulation;
import io.robomw.sim.render.PngRenderer;
import io.robomw.sim.render.RenderOptions;
import io.robomw.sim.world.WorldDescription;
import io.robomw.sim.world.WorldLoader;
import io.robomw.config.description.DescriptionException;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import javax.imageio.ImageIO;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Vehicles in a world: examples/worlds/harbour.yaml, its water, wind, current and home, and its picture. */
class VehicleWorldTest {

    private static final Path HARBOUR = Path.of("..", "examples", "worlds", "harbour.yaml");

    @Test
    void theHarbourHasItsWaterWindCurrentAndHome() {
        WorldDescription d = new WorldLoader().load(HARBOUR);
        WorldDescription.Surroundings s = d.surroundings();
        assertEquals(1, s.water().size());
        assertTrue(s.onWater(30, 5));
        assertFalse(s.onWater(10, 5));
        assertEquals(1.5, s.windX());
        assertEquals(0.15, s.currentY());
        assertEquals(50.154, s.home().latitude());
    }

    @Test
    void aWorldWithoutThemHasNoWaterAndTheSitlHome() {
        WorldDescription d = new WorldLoader().load(Path.of("..", "examples", "worlds", "arena.yaml"));
        assertEquals(WorldDescription.Surroundings.NONE, d.surroundings());
    }

    @Test
    void badWaterAndWindAreReportedWithTheirPlace(@TempDir Path dir) throws IOException {
        Path world = dir.resolve("w.yaml");
        Files.writeString(world, """
                name: w
                arena: { width: 4, height: 3 }
                water:
                  - { x: 1, y: 1, width: 2 }
                  - { polygon: [[0, 0], [1, 1]] }
                wind: { x: 99 }
                home: { latitude: 91, longitude: 0 }
                """);
        DescriptionException e = assertThrows(DescriptionException.class, () -> new WorldLoader().load(world));
        String m = e.getMessage();
        assertTrue(m.contains("height") && m.contains("polygon") && m.contains("wind") && m.contains("latitude"), m);
    }

    @Test
    void vehiclesMoveInTheWorldAsTheirDynamicsSay(@TempDir Path dir) throws IOException {
        // the two vehicles are left to this test (no platform flies them): it sets their targets itself
        try (Simulation sim = Simulation.load(HARBOUR, java.util.Set.of("copter", "boat"))) {
            SimRobot copter = sim.world().robot("copter");
            SimRobot boat = sim.world().robot("boat");
            assertNotNull(copter.vehicle());
            assertNotNull(boat.vehicle());
            assertNull(sim.world().robot("nxt").vehicle());
            copter.vehicle().arm();
            copter.vehicle().target(new VehicleTarget(0, 0, 1.5, 0));
            boat.vehicle().arm();
            boat.vehicle().target(new VehicleTarget(-2, 0, 0, 0)); // astern (half speed): west, toward the quay
            sim.runFor(Duration.ofSeconds(2));
            copter.vehicle().target(new VehicleTarget(1, 0, 0, 0));
            sim.runFor(Duration.ofSeconds(30));
            SimVehicle.Snapshot c = copter.vehicle().snapshot();
            assertFalse(c.landed());
            assertTrue(c.z() > 2.5 && c.z() < 3.5, "altitude " + c.z());
            assertTrue(copter.pose().x() > 35, "flew east: " + copter.pose());
            SimVehicle.Snapshot b = boat.vehicle().snapshot();
            assertTrue(boat.pose().x() >= 18 && boat.pose().x() < 18.3, "stopped at the quay: " + boat.pose());
            assertTrue(boat.pose().y() > 6.5, "the tide carried it north along the quay: " + boat.pose());
            assertTrue(b.battery() < 1);

            Path png = dir.resolve("harbour.png");
            PngRenderer.write(sim.world(), png, RenderOptions.DEFAULT);
            Files.copy(png, Path.of("target", "harbour-test.png"), java.nio.file.StandardCopyOption.REPLACE_EXISTING);
            BufferedImage image = ImageIO.read(png.toFile());
            assertNotNull(image);
        }
    }
}
