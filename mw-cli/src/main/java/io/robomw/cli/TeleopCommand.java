package io.robomw.cli;

import io.robomw.api.Robot;
import io.robomw.api.RobotException;
import io.robomw.api.UnsupportedActionException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParentCommand;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.InputStream;
import java.io.PrintWriter;
import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;

/**
 * {@code mw robot ROBOT teleop}: keys drive the robot, like ROS's {@code teleop_twist_keyboard}:
 * a key sets a velocity that holds until another key changes it; space stops; q (or Ctrl-C, or the
 * end of input) stops the robot and quits. The velocity is sent again every {@code --refresh}, so
 * the robot's watchdog keeps it moving, and stops it by itself if this process dies. A robot that
 * flies goes up or down a step ({@code --climb-step}) per r/PageUp or f/PageDown key, hovering
 * meanwhile; a robot that does not fly says so and drives on.
 */
@Command(mixinStandardHelpOptions = true, name = "teleop", description = {"Drive the robot with keys: w/↑ forward, s/↓ backward, a/← turn left, d/→ turn right,",
        "q/e forward while turning left/right, r/PageUp up and f/PageDown down (a robot that flies), space stop, +/- faster/slower,",
        "x or Ctrl-C stop and quit. Needs a terminal."})
final class TeleopCommand implements Callable<Integer> {

    private static final Logger LOG = LoggerFactory.getLogger(TeleopCommand.class);
    private static final int ESC = 27;
    private static final int CTRL_C = 3;
    private static final int CTRL_D = 4;

    @ParentCommand
    RobotCommand parent;

    @Option(names = "--speed", defaultValue = "0.15", description = "forward speed, m/s (default ${DEFAULT-VALUE})")
    double speed;

    @Option(names = "--turn-rate", defaultValue = "1.0", description = "turn rate, rad/s (default ${DEFAULT-VALUE})")
    double turnRate;

    @Option(names = "--refresh", defaultValue = "100ms", description = "how often the velocity is sent again (default ${DEFAULT-VALUE}; below the robot's watchdog)")
    Duration refresh;

    @Option(names = "--climb-step", defaultValue = "0.25", description = "how far r/f climb or descend, metres (default ${DEFAULT-VALUE})")
    double climbStep;

    @Option(names = "--climb-rate", defaultValue = "0.5", description = "climb and descent speed, m/s (default ${DEFAULT-VALUE})")
    double climbRate;

    @Spec
    CommandSpec spec;

    /** PageUp's code, after ESC [ 5 ~. */
    static final int PAGE_UP = 'U';
    /** PageDown's code, after ESC [ 6 ~. */
    static final int PAGE_DOWN = 'V';

    /** A velocity the keys asked for. */
    record Velocity(double linear, double angular) {
        static final Velocity STOP = new Velocity(0, 0);

        boolean moving() {
            return linear != 0 || angular != 0;
        }
    }

    @Override
    public Integer call() throws IOException, InterruptedException {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        RawTerminal terminal;
        try {
            terminal = RawTerminal.enter();
        } catch (IOException e) {
            err.println("mw robot teleop: " + e.getMessage() + "; run it in a terminal, or give single commands (mw robot ROBOT move 0.2 0.1)");
            err.flush();
            return Mw.USER_ERROR;
        }
        try (terminal; Robot robot = parent.open()) {
            return drive(robot, System.in, out);
        } catch (RobotException | IllegalArgumentException e) {
            err.println("mw robot teleop: " + Mw.oneLine(e));
            err.flush();
            return e instanceof RobotException ? 1 : Mw.USER_ERROR;
        }
    }

    /**
     * Reads keys until quit; a named thread sends the velocity they set every {@link #refresh}.
     *
     * @return 0 after a quit key or the end of input, 1 if the robot failed
     */
    int drive(Robot robot, InputStream keys, PrintWriter out) throws IOException, InterruptedException {
        AtomicReference<Velocity> wanted = new AtomicReference<>(Velocity.STOP);
        AtomicReference<Double> climb = new AtomicReference<>();
        AtomicReference<Throwable> failure = new AtomicReference<>();
        CountDownLatch quit = new CountDownLatch(1);
        Thread sender = new Thread(() -> send(robot, wanted, climb, failure, quit, out), "mw-teleop-" + robot.name());
        sender.setDaemon(true);
        out.printf("teleop %s: w/s forward/backward, a/d turn, q/e curve, r/f up/down, space stop, +/- speed, x quit%n", robot.name());
        out.flush();
        sender.start();
        double scale = 1;
        try {
            while (failure.get() == null) {
                int key = keys.read();
                if (key < 0 || key == 'x' || key == CTRL_C || key == CTRL_D) {
                    break;
                }
                if (key == ESC) {
                    key = arrow(keys);
                }
                Velocity v = switch (key) {
                    case 'w', 'A' -> new Velocity(speed * scale, 0);
                    case 's', 'B' -> new Velocity(-speed * scale, 0);
                    case 'a', 'D' -> new Velocity(0, turnRate * scale);
                    case 'd', 'C' -> new Velocity(0, -turnRate * scale);
                    case 'q' -> new Velocity(speed * scale, turnRate * scale / 2);
                    case 'e' -> new Velocity(speed * scale, -turnRate * scale / 2);
                    case ' ', 'k' -> Velocity.STOP;
                    default -> null;
                };
                if (key == 'r' || key == PAGE_UP || key == 'f' || key == PAGE_DOWN) {
                    wanted.set(Velocity.STOP);
                    // keys typed while a climb is being flown add up: r r is two steps, r f none
                    double step = (key == 'r' || key == PAGE_UP ? 1 : -1) * climbStep * scale;
                    climb.accumulateAndGet(step, (pending, more) -> pending == null ? more : pending + more);
                    continue;
                }
                if (key == '+' || key == '-') {
                    scale = Math.max(0.1, Math.min(4, scale * (key == '+' ? 1.25 : 0.8)));
                    Velocity now = wanted.get();
                    v = new Velocity(now.linear() * (key == '+' ? 1.25 : 0.8), now.angular() * (key == '+' ? 1.25 : 0.8));
                }
                if (v != null) {
                    wanted.set(v);
                    out.printf(Locale.ROOT, "%s %.2f m/s, %.2f rad/s; pose %s%n", v.moving() ? "driving" : "stopped", v.linear(), v.angular(),
                            RobotCommand.text(robot.pose()));
                    out.flush();
                }
            }
        } finally {
            // The sender ends after the command it is sending (never interrupted inside one: an
            // interrupted verb cancels its command and reports a failure, which a quit is not).
            quit.countDown();
            sender.join(refresh.toMillis() * 10 + 2000);
            robot.stop();
        }
        if (failure.get() != null) {
            out.println("the robot failed: " + Mw.oneLine(failure.get()));
            out.flush();
            return 1;
        }
        out.println("stopped; pose " + RobotCommand.text(robot.pose()));
        out.flush();
        return 0;
    }

    /** @return the arrow key after an escape: 'A' up, 'B' down, 'C' right, 'D' left, or 0 */
    private static int arrow(InputStream keys) throws IOException {
        int bracket = keys.read();
        if (bracket != '[' && bracket != 'O') {
            return 0;
        }
        int code = keys.read();
        if (code == '5' || code == '6') {
            keys.read(); // the '~'
            return code == '5' ? PAGE_UP : PAGE_DOWN;
        }
        return code >= 'A' && code <= 'D' ? code : 0;
    }

    /** The sending thread: owns the robot's motion while teleop runs; any failure stops the robot and ends the keys' loop. */
    private void send(Robot robot, AtomicReference<Velocity> wanted, AtomicReference<Double> climb, AtomicReference<Throwable> failure,
                      CountDownLatch quit, PrintWriter out) {
        boolean moving = false;
        try {
            while (quit.getCount() > 0) {
                Double metres = climb.getAndSet(null);
                if (metres != null && metres != 0) {
                    if (moving) {
                        robot.stop();
                        moving = false;
                    }
                    try {
                        robot.changeAltitude(metres, climbRate);
                        out.printf(Locale.ROOT, "%s %.2f m; pose %s%n", metres > 0 ? "climbed" : "descended", Math.abs(metres),
                                RobotCommand.text(robot.pose()));
                    } catch (UnsupportedActionException e) {
                        out.println(Mw.oneLine(e));
                    }
                    out.flush();
                }
                Velocity v = wanted.get();
                if (v.moving()) {
                    robot.drive(v.linear(), v.angular());
                    moving = true;
                } else if (moving) {
                    robot.stop();
                    moving = false;
                }
                if (quit.await(refresh.toMillis(), TimeUnit.MILLISECONDS)) {
                    break;
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } catch (Throwable t) {
            LOG.error("teleop of robot '{}' failed; stopping it", robot.name(), t);
            failure.set(t);
            try {
                robot.stop();
            } catch (RuntimeException stopFailed) {
                t.addSuppressed(stopFailed);
            }
        }
    }
}
