import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.api.SensorType;

import java.nio.file.Path;

/**
 * README's first program, as one file: drives a robot described by a robot file, reads its front
 * range sensor and prints where it thinks it is. Run it on the distribution's class path:
 *
 * <pre>
 * ./mw emulate nxt --world examples/worlds/arena.yaml --robot nxt --write-robot nxt.yaml   # a virtual NXT; leave it running
 * ./mw run examples/FirstProgram.java nxt.yaml                                              # in a second terminal
 * </pre>
 */
public class FirstProgram {

    public static void main(String[] args) {
        Path file = Path.of(args.length > 0 ? args[0] : "nxt.yaml");
        try (Robot robot = Robots.open(file)) {
            robot.move(0.50, 0.20);                       // metres, metres per second; blocks until done
            robot.turn(Math.PI / 2, 1.0);                 // radians (positive = left), radians per second
            double cm = robot.getValue(Position.FRONT, SensorType.RANGE, ReturnType.CENTIMETERS);
            robot.moveAsync(0.30, 0.10).join();           // every verb has a non-blocking ...Async form
            System.out.printf("front range %.0f cm; odometry says %s%n", cm, robot.pose());
        }
    }
}
