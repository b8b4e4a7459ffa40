package io.robomw.sim.bench;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.EmulatorStack;
import io.robomw.sim.emulator.LinkModel;
import io.robomw.sim.emulator.ev3.Ev3Emulator;
import io.robomw.sim.emulator.ev3.Ev3FullStackTest;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulator;
import io.robomw.sim.emulator.ft.intelligent.IntelligentInterfaceEmulatorTest;
import io.robomw.sim.emulator.nxt.NxtEmulator;
import io.robomw.sim.emulator.nxt.NxtEmulatorTest;
import io.robomw.sim.emulator.rcx.RcxEmulator;
import io.robomw.sim.emulator.rcx.RcxFullStackTest;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.function.BiFunction;

/**
 * How the precision of {@code move} and {@code turn} changes with the link's latency, brick by
 * brick: the real driver against its emulator on a pseudo-terminal, the world in real time, the
 * link slowed by a {@link LinkModel} of each latency (one way, per telegram) at the brick's usual
 * byte rate. For each brick and latency: {@code move(0.5 m)} from rest and {@code turn(90°)},
 * several runs, the median and the largest error of the robot's true pose.
 *
 * <p>Run on demand: {@code bench/link-latency [--runs N] [--brick NAME] [LATENCY_MS ...]} (see
 * {@code docs/bricks.md}). Not a test.
 */
public final class LinkLatencyPrecision {

    /** A brick, its robot file and the speeds it is driven at. */
    record Brick(String name, String robot, String robotName, BiFunction<Simulation, String, ? extends BrickEmulator> bind,
                 LinkModel usual, double moveSpeed, double turnRate) {
    }

    private LinkLatencyPrecision() {
    }

    /**
     * @param args {@code --runs N} (default 3), {@code --brick NAME} (the bricks whose name starts so, case aside;
     *             default all), {@code --each} (print every run's signed errors too), then one-way latencies in
     *             milliseconds (default 0 15 30 60 120)
     * @throws Exception if a run cannot start
     */
    public static void main(String[] args) throws Exception {
        int runs = 3;
        String only = null;
        boolean each = false;
        List<Integer> latencies = new ArrayList<>();
        for (int i = 0; i < args.length; i++) {
            if (args[i].equals("--runs")) {
                runs = Integer.parseInt(args[++i]);
            } else if (args[i].equals("--each")) {
                each = true;
            } else if (args[i].equals("--brick")) {
                only = args[++i].toLowerCase(Locale.ROOT);
            } else {
                latencies.add(Integer.parseInt(args[i]));
            }
        }
        if (latencies.isEmpty()) {
            latencies = List.of(0, 15, 30, 60, 120);
        }
        List<Brick> all = List.of(
                new Brick("NXT (firmware 1.29+, tacho limits)", NxtEmulatorTest.ROBOT, "nxt-1", NxtEmulator::bind, LinkModel.BLUETOOTH_SPP, 0.15, 1.0),
                new Brick("NXT (firmware before 1.29)", NxtEmulatorTest.ROBOT, "nxt-1", NxtEmulator::bindLegacyFirmware, LinkModel.BLUETOOTH_SPP, 0.15, 1.0),
                new Brick("EV3", Ev3FullStackTest.ROBOT, "ev3-1", Ev3Emulator::bind, LinkModel.BLUETOOTH_SPP, 0.15, 1.0),
                new Brick("Intelligent Interface", IntelligentInterfaceEmulatorTest.ROBOT, "ft-1", IntelligentInterfaceEmulator::bind,
                        LinkModel.serial(9600, 10), 0.15, 1.0),
                new Brick("RCX", RcxFullStackTest.ROBOT, "rcx-1", RcxEmulator::bind, LinkModel.serial(2400, 11), 0.10, 0.5));
        String prefix = only;
        List<Brick> bricks = prefix == null ? all : all.stream().filter(b -> b.name().toLowerCase(Locale.ROOT).startsWith(prefix)).toList();
        System.out.printf(Locale.ROOT, "| brick | latency each way | move 0.5 m: median error | max | turn 90°: median error | max |%n");
        System.out.printf(Locale.ROOT, "|---|---|---|---|---|---|%n");
        for (Brick brick : bricks) {
            for (int latency : latencies) {
                List<Double> moveErrors = new ArrayList<>();
                List<Double> turnErrors = new ArrayList<>();
                for (int run = 0; run < runs; run++) {
                    double[] e = trial(brick, brick.usual().withLatency(Duration.ofMillis(latency)));
                    if (each) {
                        System.out.printf(Locale.ROOT, "  %s, %d ms, run %d: move %+.1f mm, turn %+.1f°%n", brick.name(), latency, run + 1,
                                e[2] * 1000, e[3]);
                    }
                    moveErrors.add(e[0]);
                    turnErrors.add(e[1]);
                }
                System.out.printf(Locale.ROOT, "| %s | %d ms | %.1f mm | %.1f mm | %.1f° | %.1f° |%n", brick.name(), latency,
                        median(moveErrors) * 1000, max(moveErrors) * 1000, median(turnErrors), max(turnErrors));
            }
        }
    }

    /** @return the move's error (m) and the turn's error (degrees), both absolute, then both signed (past the target positive) */
    @SuppressWarnings("unchecked")
    private static double[] trial(Brick brick, LinkModel link) throws Exception {
        Path dir = Files.createTempDirectory("link-latency-");
        try (EmulatorStack<BrickEmulator> stack = new EmulatorStack<>(dir, brick.robot(), brick.robotName(),
                (BiFunction<Simulation, String, BrickEmulator>) brick.bind())) {
            stack.world(3, 0.5);
            String pty = stack.newEmulator().linkModel(link).startOnPseudoTerminal();
            stack.sim().startRealTime(1);
            Robot robot = stack.open("port: " + pty);
            robot.move(0.5, brick.moveSpeed());
            stack.awaitHalfASimulatedSecond();
            Pose afterMove = stack.truePose();
            double moveError = Math.abs(afterMove.x() - 1.0);
            robot.turn(Math.PI / 2, brick.turnRate());
            stack.awaitHalfASimulatedSecond();
            double turned = Math.toDegrees(stack.truePose().heading() - afterMove.heading());
            return new double[]{moveError, Math.abs(turned - 90), afterMove.x() - 1.0, turned - 90};
        } finally {
            try (var files = Files.walk(dir)) {
                files.sorted(java.util.Comparator.reverseOrder()).forEach(p -> p.toFile().delete());
            }
        }
    }

    private static double median(List<Double> values) {
        List<Double> sorted = new ArrayList<>(values);
        sorted.sort(Double::compare);
        int n = sorted.size();
        return n % 2 == 1 ? sorted.get(n / 2) : (sorted.get(n / 2 - 1) + sorted.get(n / 2)) / 2;
    }

    private static double max(List<Double> values) {
        return values.stream().mapToDouble(Double::doubleValue).max().orElse(Double.NaN);
    }
}
