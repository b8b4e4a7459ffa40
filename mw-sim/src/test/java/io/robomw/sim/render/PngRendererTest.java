package io.robomw.sim.render;

import io.robomw.sim.Simulation;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import javax.imageio.ImageIO;
import java.awt.Color;
import java.awt.image.BufferedImage;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HashSet;
import java.util.Set;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Pictures of a small world (see {@link TestWorld}) checked pixel by pixel where the painter must
 * have drawn something. Runs headless.
 */
class PngRendererTest {

    private static final Duration LIMIT = Duration.ofSeconds(60);
    private static final RenderOptions OPTIONS = RenderOptions.DEFAULT.withSize(640, 480);

    @TempDir
    Path dir;

    @Test
    void shouldWritePngOfRequestedSizeThatIsNotBlank() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            Path file = dir.resolve("world.png");
            PngRenderer.write(sim.world(), file, OPTIONS);
            BufferedImage image = ImageIO.read(file.toFile());
            assertEquals(640, image.getWidth());
            assertEquals(480, image.getHeight());
            assertTrue(distinctColours(image) >= 8, "background, walls, floor, patch, obstacle, robot, text...: got " + distinctColours(image));
        }
    }

    @Test
    void shouldMakeFittedHeightFollowArenaAspect() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            RenderOptions options = RenderOptions.DEFAULT.withSize(848, RenderOptions.FIT_HEIGHT);
            BufferedImage image = PngRenderer.render(sim.world(), options);
            // 4.2 × 3.2 m with walls; 800 px for 4.2 m leaves 609.5 px for 3.2 m, plus two 24 px margins.
            assertEquals(848, image.getWidth());
            assertEquals(658, image.getHeight());
        }
    }

    @Test
    void shouldDrawTrajectoryInRobotsColourAlongItsPath() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            sim.run(LIMIT, () -> sim.robot("r1").move(1.0, 0.2));
            BufferedImage image = PngRenderer.render(sim.world(), OPTIONS);
            ViewTransform view = WorldPainter.fit(sim.world().description(), 640, 480, OPTIONS.marginPx());
            Color robot = WorldPainter.robotColor(0);
            assertNear(robot, image, view.screenX(1.5), view.screenY(1.5), "halfway along the 1 m path");
            assertNear(robot, image, view.screenX(1.3), view.screenY(1.5), "a third of the way");
            assertNear(grey(0.8), image, view.screenX(1.5), view.screenY(1.3), "the floor beside the path");
        }
    }

    @Test
    void shouldLeaveTrajectoryOutWhenOptionsSaySo() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            sim.run(LIMIT, () -> sim.robot("r1").move(1.0, 0.2));
            BufferedImage image = PngRenderer.render(sim.world(), OPTIONS.withTrajectories(false));
            ViewTransform view = WorldPainter.fit(sim.world().description(), 640, 480, OPTIONS.marginPx());
            assertNear(grey(0.8), image, view.screenX(1.5), view.screenY(1.5), "bare floor where the path was");
        }
    }

    @Test
    void shouldDrawRobotBodyWallsObstacleAndDarkPatchWhereTheyAre() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 1, 1.5, 0)) {
            BufferedImage image = PngRenderer.render(sim.world(), OPTIONS);
            ViewTransform view = WorldPainter.fit(sim.world().description(), 640, 480, OPTIONS.marginPx());
            assertNear(WorldPainter.robotColor(0), image, view.screenX(0.95), view.screenY(1.53), "robot body, off its heading mark");
            assertNear(grey(0.05), image, view.screenX(0.5), view.screenY(2.5), "dark floor patch");
            assertNear(new Color(0x8A7F72), image, view.screenX(3.0), view.screenY(2.5), "box obstacle");
            assertNear(new Color(0x3C4048), image, view.screenX(-0.05), view.screenY(1.5), "left wall");
        }
    }

    @Test
    void shouldDrawSonarRayToWallOnlyWhenRaysAreShown() throws Exception {
        try (Simulation sim = TestWorld.open(dir, 3.0, 1.5, 0)) {
            sim.runFor(Duration.ofMillis(500));
            ViewTransform view = WorldPainter.fit(sim.world().description(), 640, 480, OPTIONS.marginPx());
            int x = (int) Math.floor(view.screenX(3.55));
            int y = (int) Math.floor(view.screenY(1.5));
            Color withRays = new Color(PngRenderer.render(sim.world(), OPTIONS.withRays(true)).getRGB(x, y));
            Color without = new Color(PngRenderer.render(sim.world(), OPTIONS).getRGB(x, y));
            assertTrue(withRays.getRed() > withRays.getGreen() + 40, "between the sonar and the wall the ray is red: " + withRays);
            assertEquals(grey(0.8), without, "without rays the floor shows");
        }
    }

    @Test
    void shouldDrawALeggedRobotWithItsLegsAndItsHead() throws Exception {
        // a world may name robot files in its own tree only (issue 37): the example's robot file goes beside it
        Files.copy(Path.of("../examples/robots/aibo.yaml"), dir.resolve("aibo.yaml"), java.nio.file.StandardCopyOption.REPLACE_EXISTING);
        Files.writeString(dir.resolve("dog-world.yaml"), """
                name: dog-world
                arena: { width: 4, height: 3 }
                robots:
                  - { robot: %s, name: aibo, x: 2, y: 1.5, heading: 0 }
                """.formatted("aibo.yaml"));
        try (Simulation sim = Simulation.load(dir.resolve("dog-world.yaml"))) {
            BufferedImage image = PngRenderer.render(sim.world(), OPTIONS);
            ViewTransform view = WorldPainter.fit(sim.world().description(), 640, 480, OPTIONS.marginPx());
            Color limbs = WorldPainter.robotColor(0).darker();
            // The trunk is 0.30 × 0.18 m; the head sits in front of it, the legs stick out of its sides.
            assertNear(limbs, image, view.screenX(2.21), view.screenY(1.5), "the head, in front of the trunk");
            assertNear(limbs, image, view.screenX(2.107), view.screenY(1.62), "the left front leg, beside the trunk");
            assertNear(limbs, image, view.screenX(1.893), view.screenY(1.38), "the right hind leg");
        }
    }

    @Test
    void shouldPickScaleBarOfOneTwoOrFiveTimesPowerOfTen() {
        assertEquals(1.0, WorldPainter.scaleBarMetres(100), 1e-12);
        assertEquals(2.0, WorldPainter.scaleBarMetres(37), 1e-12);
        assertEquals(0.5, WorldPainter.scaleBarMetres(200), 1e-12);
        assertEquals(10.0, WorldPainter.scaleBarMetres(12), 1e-12);
    }

    @Test
    void shouldGiveNeighbouringRobotsDifferentColours() {
        Set<Color> colours = new HashSet<>();
        for (int i = 0; i < 50; i++) {
            colours.add(WorldPainter.robotColor(i));
        }
        assertEquals(50, colours.size());
    }

    private static Color grey(double brightness) {
        int v = (int) Math.round(brightness * 255);
        return new Color(v, v, v);
    }

    private static int distinctColours(BufferedImage image) {
        Set<Integer> seen = new HashSet<>();
        for (int y = 0; y < image.getHeight(); y++) {
            for (int x = 0; x < image.getWidth(); x++) {
                seen.add(image.getRGB(x, y));
            }
        }
        return seen.size();
    }

    /** Some pixel within one pixel of (x, y) has the expected colour, give or take anti-aliasing. */
    private static void assertNear(Color expected, BufferedImage image, double x, double y, String what) {
        int cx = (int) Math.floor(x);
        int cy = (int) Math.floor(y);
        int best = Integer.MAX_VALUE;
        Color closest = null;
        for (int dy = -1; dy <= 1; dy++) {
            for (int dx = -1; dx <= 1; dx++) {
                Color c = new Color(image.getRGB(cx + dx, cy + dy));
                int d = Math.abs(c.getRed() - expected.getRed()) + Math.abs(c.getGreen() - expected.getGreen()) + Math.abs(c.getBlue() - expected.getBlue());
                if (d < best) {
                    best = d;
                    closest = c;
                }
            }
        }
        assertTrue(best <= 24, what + ": expected " + expected + " near (" + cx + ", " + cy + "), closest " + closest);
    }
}
