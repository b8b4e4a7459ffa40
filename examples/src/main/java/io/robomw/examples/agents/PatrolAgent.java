package io.robomw.examples.agents;

import io.robomw.api.Agent;
import io.robomw.api.Itinerary;
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
 * A patrol: one agent that travels an itinerary over several hosts and, at each, drives its robot
 * forward a little, reads the front range sensor and reports; it comes home with one
 * {@link Visit} per stop. A stop whose host cannot be reached is retried, then skipped (its
 * itinerary's policy), and the patrol goes on.
 *
 * <p>Send it with {@code mw dispatch --jar examples.jar --agent io.robomw.examples.agents.PatrolAgent HOST1 HOST2 HOST3}.
 */
public class PatrolAgent extends Agent {

    private static final long serialVersionUID = 1L;

    private final double step;
    private final ArrayList<Visit> visits = new ArrayList<>();

    /** Patrols with a 0.2 m step at each stop. */
    public PatrolAgent() {
        this(0.2);
    }

    /** @param step metres to drive at each stop, as text (for {@code mw dispatch --arg}) */
    public PatrolAgent(String step) {
        this(Double.parseDouble(step));
    }

    /** @param step metres to drive at each stop */
    public PatrolAgent(double step) {
        this.step = step;
        itinerary().onUnreachable(Itinerary.UnreachablePolicy.RETRY).retry(3, java.time.Duration.ofMillis(500));
    }

    /**
     * One stop of the patrol.
     *
     * @param host  the agent host
     * @param robot its robot
     * @param range the front range read after driving, metres (NaN without a range sensor)
     * @param pose  the robot's odometry after driving
     */
    public record Visit(String host, String robot, double range, Pose pose) implements Serializable {
        private static final long serialVersionUID = 1L;

        @Override
        public String toString() {
            return String.format(Locale.ROOT, "%s/%s: range %.3f m, odometry (%.3f, %.3f)", host, robot, range, pose.x(), pose.y());
        }
    }

    @Override
    public void run() {
        Robot robot = context().robot();
        robot.move(step, 0.15);
        double range = Double.NaN;
        for (SensorInfo s : robot.sensors()) {
            if (s.position() == Position.FRONT && (s.type() == SensorType.SONAR || s.type() == SensorType.INFRARED)) {
                range = robot.getValue(Position.FRONT, s.type(), ReturnType.METERS);
                break;
            }
        }
        Visit v = new Visit(context().hostName(), robot.name(), range, robot.pose());
        visits.add(v);
        context().report(v.toString());
        context().setResult(new ArrayList<>(visits));
    }

    /** @return the visits so far */
    public List<Visit> visits() {
        return List.copyOf(visits);
    }
}
