package io.robomw.console.record;

import io.robomw.console.observe.Observation;
import io.robomw.console.observe.WorldMap;
import org.junit.jupiter.api.Test;

import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;

/** The replayed picture places a robot's odometry from its start pose on the recorded map, as the live page does. */
class ReplayPictureTest {

    @Test
    void odometryIsDrawnFromTheRobotsStartPoseNotTheArenasOrigin() {
        WorldMap arena = new WorldMap("arena", 4, 3, true, 0.05, 0.8, List.of(), List.of(),
                List.of(new WorldMap.RobotMark("nxt", 0.2, 0.15, 2.6, 0.4, Math.PI / 2)));
        ReplayPicture picture = new ReplayPicture();
        picture.observe(new Observation.World(0, arena));
        picture.observe(new Observation.RobotPose(1, "nxt", 0, 0, 0, false));
        picture.observe(new Observation.RobotPose(2, "nxt", 0.5, 0, 0, false)); // 0.5 m ahead, facing +y at its start
        picture.observe(new Observation.RobotPose(2, "sim", 1.0, 1.0, 0, true)); // a true pose is the map's already
        List<double[]> nxt = picture.paths().get("nxt");
        assertArrayEquals(new double[] {2.6, 0.4, Math.PI / 2}, nxt.get(0), 1e-9);
        assertArrayEquals(new double[] {2.6, 0.9, Math.PI / 2}, nxt.get(1), 1e-9);
        assertArrayEquals(new double[] {1.0, 1.0, 0}, picture.paths().get("sim").get(0), 1e-9);
    }
}
