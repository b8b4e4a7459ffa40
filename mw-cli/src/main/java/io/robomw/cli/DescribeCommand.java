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
import io.robomw.api.spi.PlatformServices;
import io.robomw.config.yaml.MappingReader;
import io.robomw.config.yaml.YamlDocument;
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
import java.util.ArrayList;
import java.util.Comparator;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.Callable;
import java.util.regex.Pattern;
import java.util.stream.Collectors;

/**
 * {@code mw describe FILE.yaml...}: checks robot and world files and prints what the middleware
 * makes of them (geometry in motor terms, sensors, actions; a world's arena and robots). A robot
 * file gets every check {@code mw host} makes before it opens the link: the driver of its
 * platform is on the class path, and the file fits it (port names, sensor types, connection; the
 * driver's own {@link io.robomw.api.spi.PlatformProvider#check}). Every problem of a file is
 * printed, all together, before its description: a platform without a driver with the file's
 * other problems. A world file is recognised by its {@code arena:} and {@code robots:}; each robot
 * file it uses is checked and described once, with how many of its robots use it. Exit code 2
 * when a file is invalid.
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
            AwaitedFile.await(file, spec, "mw describe");
            try {
                if (isWorld(file)) {
                    status = Math.max(status, describeWorld(file, out, err));
                } else {
                    status = Math.max(status, describeRobot(file, "", out, err));
                }
            } catch (DescriptionException e) {
                err.println(e.getMessage());
                status = 2;
            } catch (IOException e) {
                err.println(file + ": cannot read it: " + e.getMessage());
                status = 2;
            }
            out.flush();
            err.flush();
        }
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

    /** How many robots of a world are listed by name and place, and how many names of the robots sharing one robot file. */
    static final int MAX_LISTED = 20;

    /**
     * Prints a world, its robots' places, and each robot file it uses once, with how many robots
     * and which use it (a swarm of 200 robots from one file is one description, not 200).
     *
     * @return 0, or 2 when a robot file has a problem
     */
    private static int describeWorld(Path file, PrintWriter out, PrintWriter err) {
        WorldDescription w = new WorldLoader().load(file);
        out.printf(Locale.ROOT, "%s: world '%s', arena %.2f × %.2f m%s, %d obstacle%s, %d floor patch%s, %d robot%s, physics %.0f Hz, seed %d%n",
                w.source(), w.name(), w.width(), w.height(), w.walls() ? " with walls" : "", w.obstacles().size(), w.obstacles().size() == 1 ? "" : "s",
                w.patches().size(), w.patches().size() == 1 ? "" : "es", w.robots().size(), w.robots().size() == 1 ? "" : "s", w.physicsHz(), w.seed());
        // The robots placed one by one come first; a swarm entry's are described by the entry.
        int single = w.swarms().isEmpty() ? w.robots().size() : w.swarms().get(0).first();
        Map<Path, List<String>> byFile = new LinkedHashMap<>();
        for (WorldDescription.RobotPlacement r : w.robots().subList(0, single)) {
            byFile.computeIfAbsent(r.description(), f -> new ArrayList<>()).add("'" + r.name() + "'");
        }
        Map<Path, Integer> counts = new LinkedHashMap<>();
        byFile.forEach((f, names) -> counts.put(f, names.size()));
        w.robots().stream().limit(Math.min(single, MAX_LISTED)).forEach(r -> out.printf(Locale.ROOT, "  robot '%s' at (%.2f, %.2f) heading %.1f°, from %s%n",
                r.name(), r.start().x(), r.start().y(), Math.toDegrees(r.start().heading()), r.description()));
        if (single > MAX_LISTED) {
            out.printf(Locale.ROOT, "  ... and %d more robots%n", single - MAX_LISTED);
        }
        for (WorldDescription.Swarm s : w.swarms()) {
            out.printf(Locale.ROOT, "  swarm '%s': %d robot%s ('%s-1' to '%s-%d') from %s, placed by seed %d in %.2f × %.2f m at (%.2f, %.2f)%n",
                    s.name(), s.count(), s.count() == 1 ? "" : "s", s.name(), s.name(), s.count(), s.robot(), s.seed(), s.width(), s.height(),
                    s.x(), s.y());
            byFile.computeIfAbsent(s.robot(), f -> new ArrayList<>()).add("swarm '" + s.name() + "' (" + s.count() + ")");
            counts.merge(s.robot(), s.count(), Integer::sum);
        }
        int status = 0;
        for (Map.Entry<Path, List<String>> group : byFile.entrySet()) {
            int n = counts.get(group.getKey());
            out.printf(Locale.ROOT, "  robot file %s, for %d robot%s: %s%n", group.getKey(), n, n == 1 ? "" : "s", listed(group.getValue()));
            status = Math.max(status, describeRobot(group.getKey(), "    ", out, err));
        }
        return status;
    }

    /** @return up to {@link #MAX_LISTED} names (quoted already), and how many more */
    static String listed(List<String> names) {
        String shown = names.stream().limit(MAX_LISTED).collect(Collectors.joining(", "));
        return names.size() > MAX_LISTED ? shown + " and " + (names.size() - MAX_LISTED) + " more" : shown;
    }

    /**
     * Checks a robot file as {@code mw host} does before it opens the link, prints every problem
     * it finds (the file's own, a platform without a driver, what its driver refuses), and then,
     * if the file could be read, what RoboMW makes of it.
     *
     * @return 0, or 2 when the file has a problem
     */
    private static int describeRobot(Path file, String indent, PrintWriter out, PrintWriter err) {
        List<DescriptionException.Problem> problems = new ArrayList<>();
        RobotDescription d = null;
        try {
            d = new RobotDescriptionLoader().load(file);
        } catch (DescriptionException e) {
            problems.addAll(e.problems());
        }
        platformProblem(file).ifPresent(problems::add);
        List<String> misfits = List.of();
        if (d != null && problems.isEmpty()) {
            misfits = DescriptionRobotFactory.provider(d)
                    .check(DescriptionRobotFactory.platformConfig(d, PlatformServices.none(), Clock.system(), io.robomw.api.spi.Cycling.OWN_THREADS));
        }
        if (!problems.isEmpty()) {
            problems.sort(Comparator.comparingInt(DescriptionException.Problem::line).thenComparingInt(DescriptionException.Problem::column));
            err.println(new DescriptionException(problems).getMessage());
        }
        if (!misfits.isEmpty()) {
            err.println(DescriptionRobotFactory.misfit(d, misfits));
        }
        if (d != null) {
            print(out, d, indent);
        }
        return problems.isEmpty() && misfits.isEmpty() ? 0 : 2;
    }

    /**
     * @return the problem of a {@code platform:} that no driver on the class path has, at its place
     *         in the file, found whatever else is wrong with the file; empty if the driver is
     *         there, or the file has no readable platform (the loader says why)
     */
    private static java.util.Optional<DescriptionException.Problem> platformProblem(Path file) {
        MappingReader root;
        try {
            root = YamlDocument.read(file);
        } catch (DescriptionException e) {
            return java.util.Optional.empty();
        }
        java.util.Optional<String> platform = root.text("platform").filter(p -> !p.isBlank());
        if (platform.isEmpty()) {
            return java.util.Optional.empty();
        }
        org.yaml.snakeyaml.error.Mark at = root.mark("platform");
        return DescriptionRobotFactory.missingDriver(platform.get())
                .map(why -> new DescriptionException.Problem(file.toString(), at.getLine() + 1, at.getColumn() + 1, "'platform': " + why));
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
