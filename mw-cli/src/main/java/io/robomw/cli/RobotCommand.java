package io.robomw.cli;

import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.Robots;
import io.robomw.api.SensorType;
import io.robomw.api.UnsupportedActionException;
import io.robomw.api.spi.PlatformServices;
import io.robomw.config.robot.ConnectionOverride;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.ParentCommand;
import picocli.CommandLine.Spec;

import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.Callable;

/**
 * {@code mw robot ROBOT VERB ...}: one command to a robot from the keyboard, like
 * {@code ros2 topic pub --once} or {@code ros2 service call}: ROBOT is a served robot's address
 * ({@code tcp://127.0.0.1:7000/nxt}, as {@code mw host --serve} prints it) or a robot file
 * (opened with its driver, as {@code Robots.open} does). Verbs: {@code move}, {@code turn},
 * {@code takeoff}, {@code land}, {@code climb} (a robot that flies), {@code get}, {@code pose},
 * {@code stop} and {@code teleop} (keys drive it). Exit status 0 done,
 * 1 the robot failed (a link error), 2 a usage error or an action the robot cannot do.
 */
@Command(mixinStandardHelpOptions = true, name = "robot", description = {"Drive a robot from the keyboard: one command (move, turn, takeoff, land, climb, get, pose, stop), or keys (teleop).",
        "ROBOT is a served robot's address (mw host --serve prints it, e.g. tcp://127.0.0.1:7000/nxt) or a robot file.",
        "Examples: mw robot tcp://127.0.0.1:7000/nxt move 0.2 0.1    mw robot nxt.yaml get FRONT SONAR CM    mw robot nxt.yaml teleop"},
        subcommands = {RobotCommand.Move.class, RobotCommand.Turn.class, RobotCommand.TakeOff.class, RobotCommand.Land.class,
                RobotCommand.Climb.class, RobotCommand.Get.class, RobotCommand.PoseVerb.class, RobotCommand.Stop.class, TeleopCommand.class})
final class RobotCommand {

    /** Optional for picocli only, so that {@code mw robot move --help} works; every verb needs it. */
    @Parameters(index = "0", arity = "0..1", paramLabel = "ROBOT", description = "a served robot's address (tcp://HOST:PORT/NAME, mqtt://BROKER/NAME...) or a robot file")
    String target;

    @picocli.CommandLine.Spec
    CommandSpec robotSpec;

    @Option(names = "--connection", paramLabel = "KEY=VALUE", description = "with a robot file: replace a connection value, e.g. port=/dev/pts/5")
    Map<String, String> connection = new LinkedHashMap<>();

    /** @return the robot, opened: remote for an address, with its driver for a file */
    Robot open() {
        if (target == null) {
            throw new picocli.CommandLine.ParameterException(robotSpec.commandLine(), "Missing required parameter: 'ROBOT' (mw robot ROBOT VERB ...)");
        }
        if (target.contains("://")) {
            return Robots.remote(target);
        }
        Path file = Path.of(target);
        AwaitedFile.await(file, robotSpec, "mw robot");
        if (!Files.isRegularFile(file)) {
            throw new IllegalArgumentException("no robot file " + target + ", and it is no address (tcp://HOST:PORT/NAME)");
        }
        PlatformServices services = connection.isEmpty() ? PlatformServices.none()
                : PlatformServices.none().with(ConnectionOverride.class, new ConnectionOverride(connection));
        return Robots.open(file, services);
    }

    /** @return a pose for people: metres and degrees (and the altitude of a robot off the ground) */
    static String text(Pose p) {
        String plane = String.format(Locale.ROOT, "x %.3f m, y %.3f m, heading %.1f°", p.x(), p.y(), Math.toDegrees(p.heading()));
        return p.z() == 0 ? plane : plane + String.format(Locale.ROOT, ", altitude %.2f m", p.z());
    }

    /**
     * Opens the robot, runs a verb, closes it; a robot that cannot do the action is a usage error
     * (2), one whose link fails a failure (1), each one line.
     */
    abstract static class Verb implements Callable<Integer> {

        @ParentCommand
        RobotCommand parent;

        @Spec
        CommandSpec spec;

        abstract void run(Robot robot, PrintWriter out);

        @Override
        public Integer call() {
            PrintWriter out = spec.commandLine().getOut();
            PrintWriter err = spec.commandLine().getErr();
            String name = spec.qualifiedName();
            try (Robot robot = parent.open()) {
                run(robot, out);
                return 0;
            } catch (UnsupportedActionException | IllegalArgumentException e) {
                err.println(name + ": " + Mw.oneLine(e));
                return Mw.USER_ERROR;
            } catch (RobotException e) {
                err.println(name + ": " + Mw.oneLine(e));
                return 1;
            } finally {
                out.flush();
                err.flush();
            }
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "move", description = "Drive DISTANCE metres (negative: backwards) at SPEED m/s; blocks until done.")
    static final class Move extends Verb {
        @Parameters(index = "0", paramLabel = "DISTANCE", description = "metres, negative backwards")
        double distance;

        @Parameters(index = "1", paramLabel = "SPEED", description = "metres per second")
        double speed;

        @Override
        void run(Robot robot, PrintWriter out) {
            robot.move(distance, speed);
            out.println("moved " + distance + " m; pose " + text(robot.pose()));
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "takeoff", description = "Take off and climb to ALTITUDE metres (a robot that flies); blocks until there.")
    static final class TakeOff extends Verb {
        @Parameters(index = "0", paramLabel = "ALTITUDE", description = "metres above the take-off point")
        double altitude;

        @Override
        void run(Robot robot, PrintWriter out) {
            robot.takeOff(altitude);
            out.println("took off; pose " + text(robot.pose()));
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "land", description = "Land where it is (a robot that flies); blocks until it is on the ground.")
    static final class Land extends Verb {
        @Override
        void run(Robot robot, PrintWriter out) {
            robot.land();
            out.println("landed; pose " + text(robot.pose()));
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "climb", description = "Climb METRES (negative: descend) at SPEED m/s (a robot that flies); blocks until done.")
    static final class Climb extends Verb {
        @Parameters(index = "0", paramLabel = "METRES", description = "metres, negative descends")
        double metres;

        @Parameters(index = "1", paramLabel = "SPEED", defaultValue = "0.5", description = "metres per second (default ${DEFAULT-VALUE})")
        double speed;

        @Override
        void run(Robot robot, PrintWriter out) {
            robot.changeAltitude(metres, speed);
            out.println("climbed " + metres + " m; pose " + text(robot.pose()));
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "turn", description = "Turn ANGLE on the spot (positive: left) at RATE; blocks until done. ANGLE in radians, or degrees with 'deg' (90deg).")
    static final class Turn extends Verb {
        @Parameters(index = "0", paramLabel = "ANGLE", description = "radians (1.57), or degrees with deg (90deg); positive turns left")
        String angle;

        @Parameters(index = "1", paramLabel = "RATE", defaultValue = "1", description = "radians per second (default ${DEFAULT-VALUE})")
        double rate;

        @Override
        void run(Robot robot, PrintWriter out) {
            double radians = angle(angle);
            robot.turn(radians, rate);
            out.println(String.format(Locale.ROOT, "turned %.1f°; pose %s", Math.toDegrees(radians), text(robot.pose())));
        }

        static double angle(String text) {
            String t = text.strip().toLowerCase(Locale.ROOT);
            try {
                if (t.endsWith("deg") || t.endsWith("°")) {
                    return Math.toRadians(Double.parseDouble(t.replaceAll("(deg|°)$", "")));
                }
                return Double.parseDouble(t.replaceAll("rad$", ""));
            } catch (NumberFormatException e) {
                throw new IllegalArgumentException("'" + text + "' is not an angle; give radians (1.57) or degrees (90deg)");
            }
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "get", description = {"Read a sensor: by where it is and its type (get FRONT SONAR CM), or by its name (get sonar CM).",
            "Units: raw, percent, m, cm, mm, rad, deg, deg/s, rad/s, lux, db, color, bool (default raw)."})
    static final class Get extends Verb {
        @Parameters(arity = "1..3", paramLabel = "SENSOR", description = "POSITION TYPE [UNIT], or NAME [UNIT]")
        List<String> words = new ArrayList<>();

        @Override
        void run(Robot robot, PrintWriter out) {
            double value;
            ReturnType unit;
            String what;
            Position position = words.size() >= 2 ? parse(Position.class, words.get(0), false) : null;
            if (position != null) {
                SensorType type = parse(SensorType.class, words.get(1), true);
                unit = words.size() == 3 ? unit(words.get(2)) : ReturnType.RAW;
                what = position.name().toLowerCase(Locale.ROOT) + " " + type.name().toLowerCase(Locale.ROOT);
                value = robot.getValue(position, type, unit);
            } else {
                if (words.size() == 3) {
                    throw new IllegalArgumentException("'" + words.get(0) + "' is no position (" + names(Position.class) + "); give POSITION TYPE UNIT or NAME UNIT");
                }
                unit = words.size() == 2 ? unit(words.get(1)) : ReturnType.RAW;
                what = words.get(0);
                value = robot.getValue(words.get(0), unit);
            }
            out.println(what + " = " + format(value) + " " + unit.name().toLowerCase(Locale.ROOT));
        }

        private static String format(double v) {
            return v == Math.rint(v) && Math.abs(v) < 1e15 ? String.valueOf((long) v) : String.format(Locale.ROOT, "%.4f", v);
        }

        static ReturnType unit(String text) {
            String t = text.strip().toLowerCase(Locale.ROOT);
            ReturnType r = switch (t) {
                case "m" -> ReturnType.METERS;
                case "cm" -> ReturnType.CENTIMETERS;
                case "mm" -> ReturnType.MILLIMETERS;
                case "rad" -> ReturnType.RADIANS;
                case "deg" -> ReturnType.DEGREES;
                case "deg/s" -> ReturnType.DEGREES_PER_SECOND;
                case "rad/s" -> ReturnType.RADIANS_PER_SECOND;
                case "%", "pct" -> ReturnType.PERCENT;
                case "db" -> ReturnType.DECIBELS;
                case "color" -> ReturnType.COLOR_ID;
                case "bool" -> ReturnType.BOOLEAN;
                default -> null;
            };
            return r != null ? r : parse(ReturnType.class, text, true);
        }

        private static <E extends Enum<E>> E parse(Class<E> type, String text, boolean required) {
            String t = text.strip().toUpperCase(Locale.ROOT).replace('-', '_');
            for (E e : type.getEnumConstants()) {
                if (e.name().equals(t)) {
                    return e;
                }
            }
            if (!required) {
                return null;
            }
            throw new IllegalArgumentException("'" + text + "' is no " + type.getSimpleName() + "; one of " + names(type));
        }

        private static String names(Class<? extends Enum<?>> type) {
            return String.join(", ", java.util.Arrays.stream(type.getEnumConstants()).map(e -> e.name().toLowerCase(Locale.ROOT)).toList());
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "pose", description = "Print where the robot's odometry says it is.")
    static final class PoseVerb extends Verb {
        @Override
        void run(Robot robot, PrintWriter out) {
            out.println(robot.name() + ": " + text(robot.pose()));
        }
    }

    @Command(mixinStandardHelpOptions = true, name = "stop", description = "Stop every motor (safety priority: nothing running interrupts it).")
    static final class Stop extends Verb {
        @Override
        void run(Robot robot, PrintWriter out) {
            robot.stop();
            out.println(robot.name() + " stopped; pose " + text(robot.pose()));
        }
    }
}
