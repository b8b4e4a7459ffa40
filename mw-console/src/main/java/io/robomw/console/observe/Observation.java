package io.robomw.console.observe;

import java.util.List;
import java.util.Map;

/**
 * Something seen during a run, at a time: what the console shows, what a recording stores and what
 * a replay plays back. Sources (a simulated world, robots served over messaging, agent hosts, a
 * recording) make observations; {@link Observer}s (the console's view, the MCAP recorder) take
 * them. Times are nanoseconds since the Unix epoch; a simulated world's observations are stamped
 * with the wall time its run started plus its simulated time, so a fast run records (and replays)
 * in simulated time.
 */
public sealed interface Observation {

    /** @return when it was seen, ns since the Unix epoch */
    long timeNanos();

    /** The map of the world robots move in. @param map the arena */
    record World(long timeNanos, WorldMap map) implements Observation {
    }

    /**
     * Where a robot is, in {@link io.robomw.api.Pose}'s frame (z up).
     *
     * @param z     the altitude, metres (0 for robots that do not fly)
     * @param truth whether this is the simulator's true pose (else the robot's own odometry)
     */
    record RobotPose(long timeNanos, String robot, double x, double y, double z, double heading, boolean truth) implements Observation {
        /** A pose on the ground (z = 0). */
        public RobotPose(long timeNanos, String robot, double x, double y, double heading, boolean truth) {
            this(timeNanos, robot, x, y, 0, heading, truth);
        }
    }

    /** One sensor value. @param unit the unit of {@code value} ("m", "%", ...) */
    record SensorReading(long timeNanos, String robot, String sensor, double value, String unit) implements Observation {
    }

    /** A command given to a robot. @param verb move, turn, arc, drive, stop, perform... @param args its arguments by name, SI units */
    record RobotCommand(long timeNanos, String robot, String verb, Map<String, Double> args) implements Observation {
        /** Copies, keeping the arguments' order. */
        public RobotCommand {
            args = java.util.Collections.unmodifiableMap(new java.util.LinkedHashMap<>(args));
        }
    }

    /** Whether a robot answered. @param source where it is reached @param reachable whether it answered @param detail why not, or "" */
    record RobotStatus(long timeNanos, String robot, String source, boolean reachable, String detail) implements Observation {
    }

    /** What an agent host said when asked, or that it did not answer. */
    record HostSeen(long timeNanos, HostView host) implements Observation {
    }

    /**
     * Something that happened to an agent.
     *
     * @param agent  its id
     * @param kind   arrived, stop-done, stop-failed, report, departed, result, failed, disposed, retracted, present, gone
     * @param host   where (an address)
     * @param detail the report's text, the failure, the next stop...
     */
    record AgentEvent(long timeNanos, String agent, String agentClass, String kind, String host, String detail) implements Observation {
    }

    /** A message seen on a topic, as text. */
    record TopicMessage(long timeNanos, String topic, String text) implements Observation {
    }

    /** Everything in a list, for tests and replays. @param all the observations */
    record Batch(long timeNanos, List<Observation> all) implements Observation {
        /** Copies. */
        public Batch {
            all = List.copyOf(all);
        }
    }
}
