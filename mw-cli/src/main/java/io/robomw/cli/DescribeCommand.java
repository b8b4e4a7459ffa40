package io.robomw.cli;

import io.robomw.config.description.DescriptionException;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.LeggedDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.RobotDescriptionLoader;
import io.robomw.config.description.SensorSpec;
import io.robomw.config.kinematics.DifferentialKinematics;
import picocli.CommandLine.Command;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;
import picocli.CommandLine.Model.CommandSpec;

import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;

/**
 * {@code mw describe ROBOT.yaml...}: checks robot descriptions and prints what the middleware
 * makes of them (geometry in motor terms, sensors, actions). Exit code 2 when a file is invalid.
 */
@Command(name = "describe", description = "Check robot YAML files and show what RoboMW reads from them.")
final class DescribeCommand implements Callable<Integer> {

    @Parameters(arity = "1..*", paramLabel = "ROBOT.yaml", description = "robot description files")
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
                print(out, new RobotDescriptionLoader().load(file));
            } catch (DescriptionException e) {
                err.println(e.getMessage());
                status = 2;
            }
        }
        out.flush();
        err.flush();
        return status;
    }

    private static void print(PrintWriter out, RobotDescription d) {
        out.printf(Locale.ROOT, "%s: robot '%s' on platform '%s' %s, %.0f Hz cycle, watchdog %d ms, %s%n", d.source(), d.name(), d.platform(),
                d.connection().values(), 1e9 / d.cyclePeriod().toNanos(), d.watchdogTimeout().toMillis(), d.capabilities());
        d.drive().ifPresent(drive -> printDrive(out, drive));
        d.leggedDrive().ifPresent(drive -> printLeggedDrive(out, drive));
        for (SensorSpec s : d.sensors()) {
            out.printf(Locale.ROOT, "  sensor %-12s %-8s at %-11s on %s%n", s.name(), s.type(), s.position(), s.port());
        }
        d.actuators().forEach(a -> a.actions().keySet().stream().sorted()
                .forEach(action -> out.printf(Locale.ROOT, "  action %s.%s on %s%n", a.name(), action, a.port())));
        d.highLevelActions().forEach(a -> out.printf(Locale.ROOT, "  action %s%s: %s (%.1f s, uses %s)%n", a.name(),
                a.arguments().isEmpty() ? "" : a.arguments().toString().replace('[', '(').replace(']', ')'), a.command().text(),
                a.durationSeconds(), String.join(", ", a.uses())));
    }

    private static void printLeggedDrive(PrintWriter out, LeggedDrive drive) {
        out.printf(Locale.ROOT, "  drive: legged, max %.2f m/s, turns at most %.2f rad/s; gait %.1f steps/s, jitter %.0f %%, slip %.0f %%%n",
                drive.maxSpeed(), drive.maxTurnRate(), drive.gait().stepFrequency(), drive.gait().jitter() * 100, drive.gait().slip() * 100);
        out.printf(Locale.ROOT, "  move(0.5, 0.1) sends: %s%n", drive.move().render(java.util.Map.of("distance", 0.5, "speed", 0.1, "duration", 5.0)));
        out.printf(Locale.ROOT, "  turn(π/2, 1) sends: %s%n", drive.turn().render(java.util.Map.of("angle", Math.PI / 2, "speed", 1.0,
                "duration", Math.PI / 2)));
        drive.arc().ifPresent(t -> out.printf(Locale.ROOT, "  arc: %s%n", t.text()));
        drive.drive().ifPresent(t -> out.printf(Locale.ROOT, "  drive: %s%n", t.text()));
        drive.stop().ifPresent(t -> out.printf(Locale.ROOT, "  stop: %s%n", t.text()));
    }

    private static void printDrive(PrintWriter out, DifferentialDrive drive) {
        DifferentialKinematics k = new DifferentialKinematics(drive);
        out.printf(Locale.ROOT, "  drive: differential, wheels %.1f mm, track %.1f mm, gear %.2f, left %s%s, right %s%s%n",
                drive.wheelDiameter() * 1000, drive.trackWidth() * 1000, drive.gearRatio(),
                drive.left().port(), drive.left().reversed() ? " (reversed)" : "", drive.right().port(), drive.right().reversed() ? " (reversed)" : "");
        out.printf(Locale.ROOT, "  1 m forward = %.1f° per wheel motor; 90° turn = %.1f° per wheel motor; max %.2f m/s = %.0f°/s%n",
                k.move(1, drive.maxSpeed()).rightDegrees(), Math.abs(k.turn(Math.PI / 2, 1).rightDegrees()),
                drive.maxSpeed(), k.maxMotorDegreesPerSecond());
    }
}
