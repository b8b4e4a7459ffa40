package io.robomw.console.rosbridge;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.sim.SensorModel;
import io.robomw.sim.SimRobot;

import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;
import java.util.function.Supplier;

/**
 * A robot the bridge offers to ROS clients, with what it knows about its sensors beyond the
 * {@link Robot} API ({@link SensorGeometry}) and how its calls behave.
 *
 * @param robot     the robot
 * @param reach     whether its calls return at once or wait for a network
 * @param sensors   each sensor's geometry, by name; a sensor not here gets its type's defaults
 * @param truePose  for a simulated robot, where the simulator has its body, which its odometry
 *                  topic carries if the robot has no odometry of its own (wheels without encoders,
 *                  as a swarm robot's), as a simulator's ground-truth plugin publishes it;
 *                  {@code null} for any other robot
 */
public record BridgedRobot(Robot robot, Reach reach, Map<String, SensorGeometry> sensors, Supplier<Pose> truePose) {

    /** How a robot's calls behave, which decides the thread they run on. */
    public enum Reach {
        /**
         * In this process (a simulated robot, a robot opened from its file): {@code pose()} and
         * {@code drive()} return at once, so the bridge calls them on its own threads directly.
         */
        IN_PROCESS,
        /**
         * Served by another process ({@code Robots.remote}): every call is a round trip, so the
         * bridge makes them on a pool for blocking calls, one at a time per robot and kind.
         */
        REMOTE
    }

    /** Copies the map. */
    public BridgedRobot {
        Objects.requireNonNull(robot, "robot");
        Objects.requireNonNull(reach, "reach");
        sensors = Map.copyOf(sensors);
    }

    /**
     * @param robot a robot reached through {@code Robots.remote}
     * @return it, its sensors with their types' defaults
     */
    public static BridgedRobot remote(Robot robot) {
        return new BridgedRobot(robot, Reach.REMOTE, Map.of(), null);
    }

    /**
     * @param robot a robot of this process
     * @return it, its sensors with their types' defaults
     */
    public static BridgedRobot inProcess(Robot robot) {
        return new BridgedRobot(robot, Reach.IN_PROCESS, Map.of(), null);
    }

    /**
     * @param robot       a robot of this process opened from its file
     * @param description that file's description: its sensors' options give their geometry
     * @return it
     */
    public static BridgedRobot described(Robot robot, RobotDescription description) {
        Map<String, SensorGeometry> g = new LinkedHashMap<>();
        for (SensorInfo s : robot.sensors()) {
            description.sensor(s.name()).map(SensorSpec::options).ifPresent(o -> g.put(s.name(), SensorGeometry.fromOptions(s, o)));
        }
        return new BridgedRobot(robot, Reach.IN_PROCESS, g, null);
    }

    /**
     * @param robot a simulated robot
     * @param body  its body in the world: the simulator's sensor models give their geometry
     * @return it
     */
    public static BridgedRobot simulated(Robot robot, SimRobot body) {
        Map<String, SensorGeometry> g = new LinkedHashMap<>();
        for (SensorInfo s : robot.sensors()) {
            SensorModel m = body.sensors().get(s.name());
            if (m != null) {
                SensorGeometry d = SensorGeometry.defaults(s);
                boolean ranging = m.kind() == SensorModel.Kind.RANGE;
                g.put(s.name(), new SensorGeometry(d.radiation(), ranging ? m.beamWidth() : d.fieldOfView(), ranging ? m.minRange() : d.minRange(),
                        ranging ? m.maxRange() : d.maxRange(), m.rateHz(), m.mountX(), m.mountY(), m.mountAngle()));
            }
        }
        return new BridgedRobot(robot, Reach.IN_PROCESS, g, body::pose);
    }

    /**
     * @param sensor one of the robot's sensors
     * @return its geometry
     */
    public SensorGeometry geometry(SensorInfo sensor) {
        SensorGeometry g = sensors.get(sensor.name());
        return g != null ? g : SensorGeometry.defaults(sensor);
    }
}
