package {{package}};

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.Robots;

import java.nio.file.Path;
import java.util.Locale;

/**
 * A program that drives a robot: a square of 0.3 m sides, then where its odometry says it is.
 * Run it with a robot file: {@code mw run --cp target/{{artifactId}}-1.0-SNAPSHOT.jar {{package}}.{{Class}} ROBOT.yaml}.
 */
public class {{Class}} {

    /**
     * @param robot a robot that drives
     * @return where its odometry says it ended
     */
    public static Pose driveSquare(Robot robot) {
        for (int side = 0; side < 4; side++) {
            robot.move(0.3, 0.15);
            robot.turn(Math.PI / 2, 1.0);
        }
        return robot.pose();
    }

    public static void main(String[] args) {
        if (args.length != 1) {
            System.err.println("usage: {{Class}} ROBOT.yaml");
            System.exit(2);
        }
        try (Robot robot = Robots.open(Path.of(args[0]))) {
            Pose end = driveSquare(robot);
            System.out.printf(Locale.ROOT, "%s drove a square; odometry (%.3f, %.3f), heading %.1f°%n", robot.name(), end.x(), end.y(),
                    Math.toDegrees(end.heading()));
        }
    }
}
