package io.robomw.sim.emulator;

import io.robomw.api.Pose;
import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.sim.Simulation;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.function.BiFunction;
import java.util.function.BooleanSupplier;

import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The full stack the emulator tests drive: one robot in a simulated arena (facing the wall at
 * x = width, at y = 1.5), the brick emulator bound to it on a pseudo-terminal or a TCP port, and
 * the real driver opened on that by {@link Robots#open} from a robot file. The robot file is a
 * template whose {@code %s} is the inside of its {@code connection: { }} block. Closes the robot,
 * every emulator it made and the simulation.
 *
 * @param <E> the emulator
 */
public final class EmulatorStack<E extends Emulator> implements AutoCloseable {

    private final Path dir;
    private final String robotTemplate;
    private final String robotName;
    private final BiFunction<Simulation, String, E> bind;
    private final List<E> emulators = new ArrayList<>();
    private Simulation sim;
    private Robot robot;

    /**
     * @param dir           where the robot and world files go
     * @param robotTemplate the robot file, {@code %s} standing for the connection block's inside
     * @param robotName     the robot's name in the world
     * @param bind          the emulator's {@code bind(simulation, robotName)}
     */
    public EmulatorStack(Path dir, String robotTemplate, String robotName, BiFunction<Simulation, String, E> bind) {
        this.dir = dir;
        this.robotTemplate = robotTemplate;
        this.robotName = robotName;
        this.bind = bind;
    }

    /**
     * Loads the world, not yet running: an arena {@code width} × 3 m, the robot at (x, 1.5) heading 0.
     *
     * @return the simulation
     * @throws IOException if the files cannot be written
     */
    public Simulation world(double width, double x) throws IOException {
        Files.writeString(dir.resolve("body.yaml"), robotTemplate.formatted("port: /dev/unused"));
        Files.writeString(dir.resolve("world.yaml"), """
                name: %s-test
                arena: { width: %s, height: 3 }
                robots:
                  - { robot: body.yaml, name: %s, x: %s, y: 1.5, heading: 0 }
                """.formatted(robotName, width, robotName, x));
        sim = Simulation.load(dir.resolve("world.yaml"), Set.of(robotName));
        return sim;
    }

    /** @return a new emulator bound to the robot (closed with the stack), not yet started */
    public E newEmulator() {
        E e = bind.apply(sim, robotName);
        emulators.add(e);
        return e;
    }

    /** @return the emulator made last */
    public E emulator() {
        return emulators.get(emulators.size() - 1);
    }

    /**
     * Opens the real driver on a connection.
     *
     * @param connection the inside of the robot file's connection block, e.g. {@code port: /dev/pts/3}
     * @return the robot
     * @throws IOException if the file cannot be written
     */
    public Robot open(String connection) throws IOException {
        Files.writeString(dir.resolve("driver.yaml"), robotTemplate.formatted(connection));
        robot = Robots.open(dir.resolve("driver.yaml"));
        return robot;
    }

    /**
     * A 3 m arena with the robot at x, an emulator on a pseudo-terminal, the world in real time
     * at {@code speed}; the driver is not opened.
     *
     * @return the emulator's pseudo-terminal
     * @throws IOException if it cannot start
     */
    public String startOnPseudoTerminal(double x, double speed) throws IOException {
        world(3, x);
        String pty = newEmulator().startOnPseudoTerminal();
        sim.startRealTime(speed);
        return pty;
    }

    /**
     * {@link #startOnPseudoTerminal}, then the driver opened on it.
     *
     * @return the robot
     * @throws IOException if it cannot start
     */
    public Robot openOnPseudoTerminal(double x, double speed) throws IOException {
        return open("port: " + startOnPseudoTerminal(x, speed));
    }

    /**
     * An arena {@code width} × 3 m with the robot at x, an emulator on a free loopback port, the
     * world in real time at {@code speed}, the driver opened on it.
     *
     * @return the emulator's port
     * @throws IOException if it cannot start
     */
    public int openOnTcp(double width, double x, double speed) throws IOException {
        world(width, x);
        int port = newEmulator().startOnTcp("127.0.0.1", 0);
        sim.startRealTime(speed);
        open("host: 127.0.0.1, port: " + port);
        return port;
    }

    /** @return the robot the driver opened */
    public Robot robot() {
        return robot;
    }

    /** @return the simulation */
    public Simulation sim() {
        return sim;
    }

    /** @return the robot's true pose in the world */
    public Pose truePose() {
        return sim.world().robot(robotName).pose();
    }

    /**
     * Waits, checking after every world step, until the condition holds; fails after the deadline.
     *
     * @param condition what to wait for
     * @param deadline  the longest wait
     * @param what      the condition, for the failure
     * @throws InterruptedException if interrupted
     */
    public void awaitStep(BooleanSupplier condition, Duration deadline, String what) throws InterruptedException {
        CountDownLatch held = new CountDownLatch(1);
        Runnable probe = () -> {
            if (condition.getAsBoolean()) {
                held.countDown();
            }
        };
        sim.addStepListener(probe);
        try {
            assertTrue(held.await(deadline.toMillis(), TimeUnit.MILLISECONDS), what + " within " + deadline.toMillis() + " ms; robot at " + truePose());
        } finally {
            sim.removeStepListener(probe);
        }
    }

    /**
     * Waits, checking on the test's thread every millisecond, until the condition holds (for
     * conditions that ask the robot, which must not run on the world's thread); fails after the
     * deadline.
     *
     * @param condition what to wait for
     * @param deadline  the longest wait
     * @param what      the condition, for the failure
     */
    public void awaitTrue(BooleanSupplier condition, Duration deadline, String what) {
        io.robomw.testkit.Await.until(what, deadline, condition, () -> "; robot at " + truePose());
    }

    /** Waits until half a simulated second has passed (the world runs on), failing after 5 s. */
    public void awaitHalfASimulatedSecond() throws InterruptedException {
        double t0 = sim.world().time();
        awaitStep(() -> sim.world().time() >= t0 + 0.5, Duration.ofSeconds(5), "half a simulated second passed");
    }

    @Override
    public void close() {
        if (robot != null) {
            robot.close();
        }
        emulators.forEach(Emulator::close);
        if (sim != null) {
            sim.close();
        }
    }
}
