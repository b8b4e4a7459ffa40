package io.robomw.sim;

import io.robomw.api.Robot;
import io.robomw.config.description.DescriptionException;
import io.robomw.sim.world.WorldDescription.Keep;
import io.robomw.sim.world.WorldDescription.TrajectorySettings;
import io.robomw.sim.world.WorldLoader;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.atomic.AtomicReference;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A robot's trajectory keeps bounded memory however long a run is, and what it keeps is still the
 * path: the whole run ever coarser, or the most recent points; its length counts every sample.
 */
class TrajectoryTest {

    @TempDir
    Path dir;

    /** Sample i of a made-up path: on the line y = 2x, one centimetre apart. */
    private static void addSamples(Trajectory t, int from, int to) {
        for (int i = from; i < to; i++) {
            t.add(i * 0.01, i * 0.02);
        }
    }

    @Test
    void shouldThinTheWholePathWhenFullSoItStillSpansTheRunAtEvenSpacing() {
        Trajectory t = new Trajectory(new TrajectorySettings(0.1, 100, Keep.WHOLE));
        addSamples(t, 0, 10_000);
        double[] p = t.snapshot();
        int points = p.length / 2;
        assertTrue(points <= 100 && points >= 50, "between half and all of the 100 points allowed, got " + points);
        assertEquals(0.0, p[0], 1e-6, "the start is kept");
        long stride = t.stride();
        assertEquals(128, stride, "10,000 samples in at most 100 points: every 128th");
        for (int i = 0; i < points; i++) {
            assertEquals(i * stride * 0.01, p[2 * i], 1e-4, "point " + i + " is sample " + i * stride);
            assertEquals(2 * p[2 * i], p[2 * i + 1], 1e-4);
        }
        assertTrue(10_000 - 1 - (points - 1) * stride < stride, "the latest kept point is within one stride of the latest sample");
        assertEquals(9_999 * Math.hypot(0.01, 0.02), t.length(), 1e-9, "the length counts every sample, kept or not");
        assertEquals(10_000, t.samples());
    }

    @Test
    void shouldKeepOnlyTheMostRecentPointsInOrderWhenAskedTo() {
        Trajectory t = new Trajectory(new TrajectorySettings(0.1, 100, Keep.RECENT));
        addSamples(t, 0, 250);
        double[] p = t.snapshot();
        assertEquals(100, p.length / 2);
        for (int i = 0; i < 100; i++) {
            assertEquals((150 + i) * 0.01, p[2 * i], 1e-5, "oldest first: samples 150 to 249");
        }
        assertEquals(249 * Math.hypot(0.01, 0.02), t.length(), 1e-9);
    }

    @Test
    void shouldKeepNoPointsButStillMeasureTheLengthWhenTheLimitIsZero() {
        Trajectory t = new Trajectory(new TrajectorySettings(0.1, 0, Keep.WHOLE));
        addSamples(t, 0, 1000);
        assertEquals(0, t.snapshot().length);
        assertEquals(999 * Math.hypot(0.01, 0.02), t.length(), 1e-9);
        assertEquals(999 * Math.hypot(0.01, 0.02) + 0.5, t.lengthTo(999 * 0.01 + 0.3, 999 * 0.02 + 0.4), 1e-9,
                "plus the way from the latest sample to the pose now");
    }

    @Test
    void shouldGiveReadersAConsistentPathWhileTheSimulationThinsIt() throws Exception {
        for (Keep keep : Keep.values()) {
            Trajectory t = new Trajectory(new TrajectorySettings(0.1, 64, keep));
            AtomicReference<String> broken = new AtomicReference<>();
            Thread reader = new Thread(() -> {
                while (!Thread.currentThread().isInterrupted() && broken.get() == null) {
                    double[] p = t.snapshot();
                    for (int i = 0; i < p.length / 2; i++) {
                        boolean onLine = Math.abs(p[2 * i + 1] - 2 * p[2 * i]) < 1e-3;
                        boolean forwards = i == 0 || p[2 * i] > p[2 * i - 2];
                        if (!onLine || !forwards) {
                            broken.set(keep + ": point " + i + " of " + p.length / 2 + " is (" + p[2 * i] + ", " + p[2 * i + 1] + ")");
                        }
                    }
                }
            }, "trajectory-reader");
            reader.start();
            addSamples(t, 0, 200_000);
            reader.interrupt();
            reader.join(10_000);
            assertEquals(null, broken.get());
            assertTrue(t.size() <= 64);
        }
    }

    private Path world(String trajectory) throws IOException {
        Files.writeString(dir.resolve("bot.yaml"), """
                name: bot
                platform: sim
                drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: { port: B }, right: { port: C } }
                body: { length: 0.12, width: 0.12, mass: 0.3 }
                """);
        Path file = dir.resolve("world.yaml");
        Files.writeString(file, """
                name: long-run
                arena: { width: 3, height: 3 }
                physics_hz: 50
                %s
                robots:
                  - { robot: bot.yaml, name: r1, x: 1.5, y: 1.5, heading: 0 }
                """.formatted(trajectory));
        return file;
    }

    @Test
    void shouldBoundARobotsPathInALongRunAsTheWorldFileSaysAndStillDrawItAndMeasureIt() throws Exception {
        try (Simulation sim = Simulation.load(world("trajectory: { every: 0.2, max_points: 40 }"))) {
            Robot r = sim.robot("r1");
            // Ten simulated minutes of circles of 0.2 m radius at 0.1 m/s: 3000 samples at 0.2 s.
            sim.run(Duration.ofMinutes(11), () -> r.arc(0.2, 60 / 0.2, 0.1));
            SimRobot body = sim.world().robot("r1");
            Trajectory t = body.trajectory();
            assertTrue(t.size() <= 40 && t.size() >= 20, "at most 40 points, the whole run thinned: " + t.size());
            assertEquals(40, t.capacity(), "its storage grew to the world's max_points and no further");
            assertTrue(t.samples() >= 3000, "a sample every 0.2 s: " + t.samples());
            // 0.1 m/s for 600 s: 60 m of circles of 0.2 m radius, measured on 0.2 s chords (a hair shorter than the arcs).
            assertEquals(60.0, t.lengthTo(body.pose().x(), body.pose().y()), 0.3);
            double[] p = t.snapshot();
            for (int i = 0; i < p.length / 2; i++) {
                assertEquals(0.2, Math.hypot(p[2 * i] - 1.5, p[2 * i + 1] - 1.7), 0.01, "every kept point is on the circle driven");
            }
        }
    }

    @Test
    void shouldReadTheTrajectoryKeyAndNameEveryWrongValueWithItsLine() throws Exception {
        var d = new WorldLoader().load(world("trajectory: { every: 0.5, max_points: 20, keep: recent }"));
        assertEquals(new TrajectorySettings(0.5, 20, Keep.RECENT), d.trajectories());
        assertEquals(TrajectorySettings.DEFAULT, new WorldLoader().load(world("")).trajectories());
        DescriptionException e = assertThrows(DescriptionException.class,
                () -> new WorldLoader().load(world("trajectory: { every: 0, max_points: -1, keep: sideways, colour: red }")));
        assertEquals(4, e.problems().size(), e::getMessage);
        String all = e.getMessage();
        for (String key : new String[] {"trajectory.every", "trajectory.max_points", "trajectory.keep", "colour"}) {
            assertTrue(all.contains(key), key + " in: " + all);
        }
        assertTrue(e.problems().stream().allMatch(p -> p.line() == 4), all);
    }
}
