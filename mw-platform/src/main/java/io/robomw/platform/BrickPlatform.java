package io.robomw.platform;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.brick.LinkAgent;
import io.robomw.platform.brick.LinkState;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensors;
import io.robomw.platform.sensor.SensorPlatform;

import java.io.IOException;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;

/**
 * A running robot platform assembled from the Platform Layer's parts: an
 * {@link ExecutionActionThread}, a driver's {@link MotorPlatform} and
 * {@link SensorPlatform}, and the {@link LinkAgent} that owns the brick's link. Drivers'
 * {@code PlatformProvider}s build one of these; the Configuration Layer sees only
 * {@link RobotPlatform}.
 *
 * <p>With {@link Cycling#OWN_THREADS}, {@link #start()} starts the action thread
 * ({@code <robot>-action}) and the link agent's thread ({@code <robot>-link}); with
 * {@link Cycling#BY_OWNER} (a simulation) it starts none: the owner cycles the action thread, and
 * the agent runs inline after each cycle. Commands are refused while the link is down or after
 * the platform has failed (one of its threads died of a failure it could not survive), with an
 * error that says which.
 */
public final class BrickPlatform implements RobotPlatform {

    private final PlatformConfig config;
    private final ExecutionActionThread actionThread;
    private final MotorPlatform motors;
    private final Sensors sensors;
    private final LinkAgent agent;

    /**
     * Creates every sensor of the description, and the link agent that takes the channel over.
     *
     * @param config         the platform's configuration
     * @param motors         the driver's motor platform
     * @param sensorPlatform the driver's sensor platform
     * @param channel        the brick's channel, or {@code null} for a platform without I/O
     * @param link           closed last (a driver's goodbye, then the channel), or {@code null} to close the channel
     * @throws IOException if a sensor cannot be set up
     */
    public BrickPlatform(PlatformConfig config, MotorPlatform motors, SensorPlatform sensorPlatform, BrickChannel channel,
                         AutoCloseable link) throws IOException {
        this.config = config;
        this.motors = motors;
        this.actionThread = new ExecutionActionThread(config.robotName(), config.clock(), config.cyclePeriod(), config.failures());
        this.sensors = sensorPlatform.createSensors(config.sensors());
        this.agent = new LinkAgent(config, actionThread, motors, channel, link);
    }

    /** @return the execution action thread, which a simulation cycles itself */
    public ExecutionActionThread actionThread() {
        return actionThread;
    }

    /** @return the motor platform */
    public MotorPlatform motors() {
        return motors;
    }

    /** @return the link's state, as its agent keeps it */
    public LinkState linkState() {
        return agent.state();
    }

    /**
     * Starts the threads, for {@link Cycling#OWN_THREADS}; a simulation cycles its platforms itself.
     *
     * @return this
     */
    public BrickPlatform start() {
        if (config.cycling() == Cycling.OWN_THREADS) {
            agent.start();
            actionThread.start();
        }
        return this;
    }

    /** @return why the link agent's thread died, if it did */
    public Optional<RobotLinkException> linkThreadFailure() {
        return agent.failure();
    }

    /** @return how many times the driver threw something other than an I/O failure */
    public long driverErrors() {
        return agent.driverErrors();
    }

    /** @return why a command cannot be run now (the platform failed, the link is down), or {@code null} */
    private RobotLinkException refusal(String command) {
        Optional<RobotLinkException> failed = agent.failure();
        if (failed.isPresent()) {
            return new RobotLinkException("robot '" + config.robotName() + "' has failed: " + failed.get().getMessage()
                    + "; " + command + " (close the robot and open it again)", failed.get());
        }
        if (agent.state() != LinkState.UP) {
            return linkDown(command);
        }
        return null;
    }

    private RobotLinkException linkDown(String command) {
        return new RobotLinkException("robot '" + config.robotName() + "': its link " + agent.describe() + " is down; " + command, null);
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        String notRun = "command '" + command.name() + "' was not run";
        RobotLinkException refused = refusal(notRun);
        if (refused != null) {
            return CompletableFuture.failedFuture(refused);
        }
        CompletableFuture<Void> queued = agent.submitWhileUp(motors.container(command));
        return queued != null ? queued : CompletableFuture.failedFuture(linkDown(notRun)); // lost since the check
    }

    /**
     * Runs a command nobody waits for: a {@code drive} (every target continuous) goes through the
     * motor platform's refresh slot instead of a container per call ({@link MotorPlatform#submitDetached}),
     * in its place among the other commands; when the link is down or the platform has failed, it
     * is dropped, as {@link #run} refuses it.
     */
    @Override
    public void runDetached(MotorCommand command) {
        if (agent.failure().isPresent()) {
            return;
        }
        agent.submitDetachedWhileUp(command);
    }

    /**
     * Stops every motor: a safety-priority container brakes them all in the next cycle.
     *
     * @return completes once the link agent has written the batch carrying the brakes (on its own
     *         thread; inline, within the cycle that applied the stop) and the stop no longer holds
     *         the motors (a command submitted then is admitted as usual); fails with
     *         {@link RobotLinkException} naming the robot if the link is down or fails first, or the
     *         platform has failed or is closed. The stop is queued all the same: a link that comes
     *         back brakes the motors first.
     */
    @Override
    public CompletableFuture<Void> stopAll() {
        CompletableFuture<Void> handed = new CompletableFuture<>();
        RobotLinkException refused = refusal("its stop was not handed to the hardware; it goes out when the link returns");
        if (refused != null) {
            handed.completeExceptionally(refused);
        }
        // Refused by a failed or closed action thread (a newer stop that took over hands itself over).
        return actionThread.submitStop(motors.stopContainer(handed), handed, e -> new RobotLinkException("robot '" + config.robotName()
                + "': its stop could not be handed to the hardware: " + e.getMessage(), e));
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        CompletableFuture<Double> read = sensors.readRaw(sensorName);
        if (read == null) {
            return CompletableFuture.failedFuture(new IllegalArgumentException("robot '" + config.robotName() + "' has no sensor '" + sensorName + "'"));
        }
        return read;
    }

    @Override
    public double motorDegrees(String port) {
        return motors.motorDegrees(port);
    }

    @Override
    public boolean hasEncoder(String port) {
        return motors.ports().contains(port) && motors.hasEncoder(port);
    }

    /**
     * Stops every command (the action thread ends them, waiting until its thread has ended), then
     * the link agent hands the stops to the hardware, leaves every output idle (coasting, as the
     * bricks' own tools do when a program stops) and closes the link.
     */
    @Override
    public void close() {
        actionThread.close();
        agent.close();
    }
}
