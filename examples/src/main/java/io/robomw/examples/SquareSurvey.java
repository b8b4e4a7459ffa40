package io.robomw.examples;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;

import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/**
 * A platform-independent program: drives a square and samples the robot's front range sensor at
 * each corner. It knows nothing of the robot but its {@link Robot} interface; the same class
 * drives a LEGO NXT or EV3, a fischertechnik Intelligent Interface or TXT, a Sony Aibo, or a
 * simulated robot, with only the robot's YAML file changed. It asks for the distance ahead as
 * {@link SensorType#RANGE}, which whatever range finder the robot has at its front answers: an
 * ultrasonic sensor on the LEGO bricks, an infra-red one on the fischertechnik interface and the
 * Aibo's head, a laser in a simulated world.
 *
 * <p>Run it: {@code java ... io.robomw.examples.SquareSurvey ROBOT.yaml [SIDE_METRES]}.
 *
 * @param side  side of the square, metres
 * @param speed metres per second
 */
public record SquareSurvey(double side, double speed) {

    /**
     * What the robot saw.
     *
     * @param ranges front range at each corner, metres (empty if the robot has no front range sensor)
     * @param pose   the robot's own odometry at the end (origin: where it started), if it has encoders
     */
    public record Report(List<Double> ranges, Pose pose) {
    }

    /**
     * Drives the square (four sides, four quarter turns left) and samples at each corner.
     *
     * @param robot the robot
     * @return the samples and the final odometry pose
     */
    public Report run(Robot robot) {
        boolean seesAhead = hasFrontRange(robot);
        List<Double> ranges = new ArrayList<>();
        for (int i = 0; i < 4; i++) {
            robot.move(side, speed);
            robot.turn(Math.PI / 2, 1.0);
            if (seesAhead) {
                ranges.add(robot.getValue(Position.FRONT, SensorType.RANGE, ReturnType.METERS));
            }
        }
        return new Report(ranges, robot.pose());
    }

    private static boolean hasFrontRange(Robot robot) {
        for (SensorInfo s : robot.sensors()) {
            if (s.position() == Position.FRONT && SensorType.RANGE.matches(s.type())) {
                return true;
            }
        }
        return false;
    }

    /**
     * @param args the robot's YAML file, and optionally the side in metres (default 0.3)
     */
    public static void main(String[] args) {
        if (args.length < 1) {
            System.err.println("usage: SquareSurvey ROBOT.yaml [SIDE_METRES]");
            System.exit(2);
        }
        double side = args.length > 1 ? Double.parseDouble(args[1]) : 0.3;
        try (Robot robot = Robots.open(Path.of(args[0]))) {
            Report r = new SquareSurvey(side, 0.15).run(robot);
            System.out.printf(Locale.ROOT, "%s: ranges %s m, odometry %s%n", robot.name(), r.ranges(), r.pose());
        }
    }
}
