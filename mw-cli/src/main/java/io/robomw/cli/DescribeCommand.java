package io.robomw.cli;

import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.config.robot.DescriptionRobotFactory;
import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.PlatformServices;
import io.robomw.sim.world.WorldDescription;
import io.robomw.sim.world.WorldLoader;
import picocli.CommandLine.Command;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;
import picocli.CommandLine.Model.CommandSpec;

import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.regex.Pattern;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;

/**
 * {@code mw describe FILE.yaml...}: checks robot and world files and prints what the middleware
 * makes of them (geometry in motor terms, sensors, actions; a world's arena and robots). A robot
 * file gets every check {@code mw host} makes before it opens the link: the driver of its
 * platform is on the class path, and the file fits it (port names, sensor types, connection; the
 * driver's own {@link io.robomw.api.spi.PlatformProvider#check}). A world file is recognised by
 * its {@code arena:} and {@code robots:} and each of its robot files is checked. Exit code 2 when
 * a file is invalid.
 */
@Command(mixinStandardHelpOptions = true, name = "describe", description = {"Check robot and world YAML files and show what RoboMW reads from them.",
        "A robot file gets every check mw host makes before it opens the link (driver present, port names, sensor types); a world file's robots too."})
final class DescribeCommand implements Callable<Integer> {

    /** A top-level key only world files have. */
    private static final Pattern WORLD_KEY = Pattern.compile("(?m)^(arena|robots|obstacles|physics_hz)\\s*:");

    @Parameters(arity = "1..*", paramLabel = "FILE.yaml", description = "robot or world description files")
    private List<Path> files;

    @Spec
    private CommandSpec spec;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        int status = 0;
        for (Path file : files) {
            try {
                if (isWorld(file)) {
                    status = Math.max(status, describeWorld(file, out, err));
                } else {
                    status = Math.max(status, describeRobot(new RobotDescriptionLoader().load(file), "", out, err));
                }
            } catch (DescriptionException e) {
                err.println(e.getMessage());
                status = 2;
            } catch (IOException e) {
                err.println(file + ": cannot read it: " + e.getMessage());
                status = 2;
            }
        }
        out.flush();
        err.flush();
        return status;
    }

    /** @return whether the file is a world (it has a key only world files have); a file that cannot be read is left to the loader */
    static boolean isWorld(Path file) throws IOException {
        if (!Files.isRegularFile(file)) {
            return false;
        }
        try (java.io.Reader r = Files.newBufferedReader(file, StandardCharsets.UTF_8)) {
            char[] head = new char[64 * 1024];
            int n = r.read(head);
            return n > 0 && WORLD_KEY.matcher(new String(head, 0, n)).find();
        } catch (java.nio.charset.CharacterCodingException e) {
            return false;
        }
    }

    private static int describeWorld(Path file, PrintWriter out, PrintWriter err) {
        WorldDescription w = new WorldLoader().load(file);
        out.printf(Locale.ROOT, "%s: world '%s', arena %.2f × %.2f m%s, %d obstacle%s, %d floor patch%s, %d robot%s, physics %.0f Hz, seed %d%n",
                w.source(), w.name(), w.width(), w.height(), w.walls() ? " with walls" : "", w.obstacles().size(), w.obstacles().size() == 1 ? "" : "s",
                w.patches().size(), w.patches().size() == 1 ? "" : "es", w.robots().size(), w.robots().size() == 1 ? "" : "s", w.physicsHz(), w.seed());
        int status = 0;
        RobotDescriptionLoader loader = new RobotDescriptionLoader();
        for (WorldDescription.RobotPlacement r : w.robots()) {
            out.printf(Locale.ROOT, "  robot '%s' at (%.2f, %.2f) heading %.1f°, from %s%n", r.name(), r.start().x(), r.start().y(),
                    Math.toDegrees(r.start().heading()), r.description());
            try {
                status = Math.max(status, describeRobot(loader.load(r.description()), "    ", out, err));
            } catch (DescriptionException e) {
                err.println(e.getMessage());
                status = 2;
            }
        }
        return status;
    }

    /** Prints a robot, then runs its platform's checks; @return 0, or 2 when the file does not fit its platform */
    private static int describeRobot(RobotDescription d, String indent, PrintWriter out, PrintWriter err) {
        print(out, d, indent);
        List<String> problems;
        try {
            PlatformProvider provider = DescriptionRobotFactory.provider(d);
            problems = provider.check(DescriptionRobotFactory.platformConfig(d, PlatformServices.none(), Clock.system(), io.robomw.api.spi.Cycling.OWN_THREADS));
        } catch (RobotException e) {
            err.println(e.getMessage());
            return 2;
        }
        if (!problems.isEmpty()) {
            err.println(DescriptionRobotFactory.misfit(d, problems));
            return 2;
        }
        return 0;
    }

    private static void print(PrintWriter out, RobotDescription d, String indent) {
        out.printf(Locale.ROOT, indent + "%s: robot '%s' on platform '%s' %s, %.0f Hz cycle, watchdog %d ms, %s%n", d.source(), d.name(), d.platform(),
                d.connection().values(), 1e9 / d.cyclePeriod().toNanos(), d.watchdogTimeout().toMillis(), d.capabilities());
        d.drive().ifPresent(drive -> printDrive(out, drive, indent));
        d.leggedDrive().ifPresent(drive -> printLeggedDrive(out, drive, indent));
        d.vehicleDrive().ifPresent(drive -> printVehicleDrive(out, drive, indent));
        for (SensorSpec s : d.sensors()) {
            out.printf(Locale.ROOT, indent + "  sensor %-12s %-8s at %-11s on %s%n", s.name(), s.type(), s.position(), s.port());
        }
        d.actuators().forEach(a -> a.actions().keySet().stream().sorted()
                .forEach(action -> out.printf(Locale.ROOT, indent + "  action %s.%s on %s%n", a.name(), action, a.port())));
        d.highLevelActions().forEach(a -> out.printf(Locale.ROOT, indent + "  action %s%s: %s (%.1f s, uses %s)%n", a.name(),
                a.arguments().isEmpty() ? "" : a.arguments().toString().replace('[', '(').replace(']', ')'), a.command().text(),
                a.durationSeconds(), String.join(", ", a.uses())));
    }

    private static void printLeggedDrive(PrintWriter out, LeggedDrive drive, String indent) {
        out.printf(Locale.ROOT, indent + "  drive: legged, max %.2f m/s, turns at most %.2f rad/s; gait %.1f steps/s, jitter %.0f %%, slip %.0f %%%n",
                drive.maxSpeed(), drive.maxTurnRate(), drive.gait().stepFrequency(), drive.gait().jitter() * 100, drive.gait().slip() * 100);
        out.printf(Locale.ROOT, indent + "  move(0.5, 0.1) sends: %s%n", drive.move().render(java.util.Map.of("distance", 0.5, "speed", 0.1, "duration", 5.0)));
        out.printf(Locale.ROOT, indent + "  turn(π/2, 1) sends: %s%n", drive.turn().render(java.util.Map.of("angle", Math.PI / 2, "speed", 1.0,
                "duration", Math.PI / 2)));
        drive.arc().ifPresent(t -> out.printf(Locale.ROOT, indent + "  arc: %s%n", t.text()));
        drive.drive().ifPresent(t -> out.printf(Locale.ROOT, indent + "  drive: %s%n", t.text()));
        drive.stop().ifPresent(t -> out.printf(Locale.ROOT, indent + "  stop: %s%n", t.text()));
    }

    private static void printVehicleDrive(PrintWriter out, io.robomw.config.description.VehicleDrive drive, String indent) {
        boolean air = drive.medium() == io.robomw.config.description.VehicleDrive.Medium.AIR;
        out.printf(Locale.ROOT, indent + "  drive: vehicle in the %s, autopilot %s, max %.2f m/s, turns at most %.2f rad/s%s, acceptance radius %.2f m%n",
                drive.medium().yamlName(), drive.autopilot().yamlName(), drive.maxSpeed(), drive.maxTurnRate(),
                air ? String.format(Locale.ROOT, ", climbs at most %.2f m/s, takes off to %.1f m", drive.maxClimbRate(), drive.takeoffAltitude()) : "",
                drive.acceptanceRadius());
        String guided = drive.autopilot() == io.robomw.config.description.VehicleDrive.Autopilot.PX4 ? "OFFBOARD (PX4 main mode 6, after a second of setpoints)"
                : air ? "GUIDED (ArduCopter mode 4)" : "GUIDED (Rover mode 15)";
        out.printf(Locale.ROOT, indent + "  move(2, 1) sends: a position target 2 m ahead in %s, streamed at 20 Hz until within %.2f m%n", guided,
                drive.acceptanceRadius());
        out.printf(Locale.ROOT, indent + "  turn(π/2, 1) sends: a yaw target 90° left; drive(v, w): velocity and yaw-rate targets%s%n",
                air ? "; takeOff, land, changeAltitude: NAV_TAKEOFF, NAV_LAND, an altitude target" : "; it cannot take off, land or climb");
    }

    private static void printDrive(PrintWriter out, DifferentialDrive drive, String indent) {
        DifferentialKinematics k = new DifferentialKinematics(drive);
        out.printf(Locale.ROOT, indent + "  drive: differential, wheels %.1f mm, track %.1f mm, gear %.2f, left %s%s, right %s%s%n",
                drive.wheelDiameter() * 1000, drive.trackWidth() * 1000, drive.gearRatio(),
                drive.left().port(), drive.left().reversed() ? " (reversed)" : "", drive.right().port(), drive.right().reversed() ? " (reversed)" : "");
        out.printf(Locale.ROOT, indent + "  1 m forward = %.1f° per wheel motor; 90° turn = %.1f° per wheel motor; max %.2f m/s = %.0f°/s%n",
                k.move(1, drive.maxSpeed()).rightDegrees(), Math.abs(k.turn(Math.PI / 2, 1).rightDegrees()),
                drive.maxSpeed(), k.maxMotorDegreesPerSecond());
    }
}
