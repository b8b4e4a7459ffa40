package {{package}};

import io.robomw.api.Agent;
import io.robomw.api.Pose;
import io.robomw.api.Robot;

import java.util.ArrayList;
import java.util.Locale;

/**
 * A mobile agent: at each host it is sent to it drives that host's robot forward, reports what
 * its odometry says, and comes home with one line per stop.
 *
 * <p>Send a clone to each of two hosts:
 * {@code mw dispatch --jar target/{{artifactId}}-1.0-SNAPSHOT.jar --agent {{package}}.{{Class}} --clone HOST1 HOST2}
 * ({@code --arg 0.3} drives 0.3 m instead of 0.2).
 */
public class {{Class}} extends Agent {

    private static final long serialVersionUID = 1L;

    private final double distance;
    private final ArrayList<String> stops = new ArrayList<>();

    /** Drives 0.2 m at each stop. */
    public {{Class}}() {
        this(0.2);
    }

    /** @param distance metres to drive at each stop, as text (mw dispatch --arg) */
    public {{Class}}(String distance) {
        this(Double.parseDouble(distance));
    }

    /** @param distance metres to drive at each stop */
    public {{Class}}(double distance) {
        this.distance = distance;
    }

    @Override
    public void run() {
        Robot robot = context().robot();
        robot.move(distance, 0.1);
        Pose p = robot.pose();
        String stop = String.format(Locale.ROOT, "%s at %s drove %.2f m; odometry (%.3f, %.3f)", robot.name(), context().hostName(), distance, p.x(), p.y());
        stops.add(stop);
        context().report(stop);
        context().setResult(new ArrayList<>(stops));
    }
}
