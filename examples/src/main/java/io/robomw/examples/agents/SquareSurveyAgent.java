package io.robomw.examples.agents;

import io.robomw.api.Agent;
import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;

import java.io.Serializable;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/**
 * The paper's demonstration agent (section IV): sent, cloned, to several robots, it drives a square
 * on each, samples the robot's front range sensor along the way, and brings the samples home. It
 * knows nothing of the robot but the {@link Robot} interface, so the same class drives a LEGO NXT,
 * a fischertechnik interface, a simulated robot, a boat or a drone: a robot that flies
 * ({@link Capability#AIR}) takes off to {@value #FLYING_ALTITUDE} m first and lands at the end.
 *
 * <p>Send it with {@code mw dispatch --jar examples.jar --agent io.robomw.examples.agents.SquareSurveyAgent --clone HOST...}
 * ({@code --arg 0.4} sets the side in metres).
 */
public class SquareSurveyAgent extends Agent {

    private static final long serialVersionUID = 1L;
    private static final double SPEED = 0.15;
    private static final int SAMPLES_PER_SIDE = 4;
    /** The altitude a robot that flies surveys at, metres. */
    public static final double FLYING_ALTITUDE = 2.0;

    private final double side;

    /** A square of 0.4 m sides. */
    public SquareSurveyAgent() {
        this(0.4);
    }

    /** @param side the side of the square, metres, as text (for {@code mw dispatch --arg}) */
    public SquareSurveyAgent(String side) {
        this(Double.parseDouble(side));
    }

    /** @param side the side of the square, metres */
    public SquareSurveyAgent(double side) {
        if (!(side > 0 && side <= 2)) {
            throw new IllegalArgumentException(side + " was supplied for side: side must be in (0, 2] metres");
        }
        this.side = side;
    }

    /**
     * One range sample.
     *
     * @param x     where the robot was (its odometry), metres
     * @param y     where the robot was, metres
     * @param range what its front range sensor read, metres
     */
    public record Sample(double x, double y, double range) implements Serializable {
        private static final long serialVersionUID = 1L;

        @Override
        public String toString() {
            return String.format(Locale.ROOT, "(%.2f, %.2f) %.2f m", x, y, range);
        }
    }

    /**
     * What the agent brings home.
     *
     * @param robot           the robot's name
     * @param host            the agent host it ran on
     * @param distanceDriven  metres driven (what it asked for)
     * @param finalOdometry   where the robot's own odometry puts it at the end (origin: its pose at the start)
     * @param odometryClosure how far from the start its odometry says it ended, metres (0 for a perfect square)
     * @param samples         the range samples
     */
    public record Survey(String robot, String host, double distanceDriven, Pose finalOdometry, double odometryClosure,
                         List<Sample> samples) implements Serializable {
        private static final long serialVersionUID = 1L;
    }

    @Override
    public void run() {
        Robot robot = context().robot();
        SensorType range = frontRange(robot);
        boolean flies = robot.capabilities().contains(Capability.AIR);
        if (flies) {
            robot.takeOff(FLYING_ALTITUDE);
            context().report(String.format(Locale.ROOT, "%s: took off to %.1f m", robot.name(), FLYING_ALTITUDE));
        }
        robot.resetPose(Pose.ORIGIN);
        List<Sample> samples = new ArrayList<>();
        double driven = 0;
        for (int sideIndex = 0; sideIndex < 4; sideIndex++) {
            for (int k = 0; k < SAMPLES_PER_SIDE; k++) {
                robot.move(side / SAMPLES_PER_SIDE, SPEED);
                driven += side / SAMPLES_PER_SIDE;
                if (range != null) {
                    Pose p = robot.pose();
                    samples.add(new Sample(p.x(), p.y(), robot.getValue(Position.FRONT, range, ReturnType.METERS)));
                }
            }
            robot.turn(Math.PI / 2, 1.0);
            context().report(String.format(Locale.ROOT, "%s: side %d of 4 done, %d samples", robot.name(), sideIndex + 1, samples.size()));
        }
        Pose end = robot.pose();
        if (flies) {
            robot.land();
        }
        context().setResult(new Survey(robot.name(), context().hostName(), driven, end, end.distanceTo(Pose.ORIGIN), samples));
    }

    private static SensorType frontRange(Robot robot) {
        for (SensorInfo s : robot.sensors()) {
            if (s.position() == Position.FRONT && SensorType.RANGE.matches(s.type())) {
                return SensorType.RANGE;
            }
        }
        return null;
    }
}
