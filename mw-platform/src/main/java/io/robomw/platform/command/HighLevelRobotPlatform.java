package io.robomw.platform.command;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.HighLevelCommand;
import io.robomw.api.spi.HighLevelPlatform;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.exec.Container;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.CompletableFuture;

/**
 * A running platform for a robot that moves by its firmware's own commands, assembled from the
 * Platform Layer's parts as {@link io.robomw.platform.BrickPlatform} is for bricks: an
 * {@link ExecutionActionThread}, a driver's {@link HighLevelCommandPlatform} and
 * {@link SensorPlatform}, and the link they talk over. It takes {@link HighLevelCommand}s and
 * refuses motor commands: the robot has no motors of its own to drive by degrees.
 *
 * <p>The driver reports its link with {@link #linkFailed} (every command ends with
 * {@link RobotLinkException} and new ones are refused until {@link #linkRestored}).
 */
public final class HighLevelRobotPlatform implements RobotPlatform, HighLevelPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(HighLevelRobotPlatform.class);

    private final PlatformConfig config;
    private final ExecutionActionThread actionThread;
    private final HighLevelCommandPlatform commands;
    private final Map<String, Sensor> sensors = new LinkedHashMap<>();
    private final AutoCloseable link;
    private volatile boolean linkDown;
    /** Held while the link's failure is reported and while a command is handed over only if the link is up. */
    private final Object linkChange = new Object();
    private volatile boolean closed;

    /**
     * Creates every sensor of the description.
     *
     * @param config         the platform's configuration
     * @param commands       the driver's command platform
     * @param sensorPlatform the driver's sensor platform
     * @param link           closed last, after the running commands were stopped; or {@code null}
     * @throws IOException if a sensor cannot be set up
     */
    public HighLevelRobotPlatform(PlatformConfig config, HighLevelCommandPlatform commands, SensorPlatform sensorPlatform,
                                  AutoCloseable link) throws IOException {
        this.config = config;
        this.commands = commands;
        this.link = link;
        this.actionThread = new ExecutionActionThread(config.robotName(), config.clock(), config.cyclePeriod(), config.failures());
        for (SensorChannel channel : config.sensors()) {
            sensors.put(channel.name(), sensorPlatform.createSensor(channel));
        }
    }

    /** @return the execution action thread, which a simulation cycles itself */
    public ExecutionActionThread actionThread() {
        return actionThread;
    }

    /**
     * Starts the execution action thread, if the clock is the wall clock; a simulation cycles a
     * platform on a simulated clock itself.
     *
     * @return this
     */
    public HighLevelRobotPlatform start() {
        if (config.cycling() == io.robomw.api.spi.Cycling.OWN_THREADS) {
            actionThread.start();
        }
        return this;
    }

    /**
     * The link failed: every command ends with {@link RobotLinkException} at the next cycle, and
     * new ones are refused until {@link #linkRestored()}.
     *
     * @param link  the link, for messages
     * @param cause what happened
     */
    public void linkFailed(String link, Throwable cause) {
        boolean was;
        synchronized (linkChange) {
            was = linkDown;
            linkDown = true;
            actionThread.linkFailed(link, cause);
        }
        if (!was) {
            LOG.warn("robot '{}': link {} failed: {}", config.robotName(), link, cause.getMessage());
        }
    }

    /** The link works again: commands are taken again. */
    public void linkRestored() {
        if (linkDown) {
            linkDown = false;
            LOG.info("robot '{}': link restored", config.robotName());
        }
    }

    /** @return whether the link is down (commands are refused) */
    public boolean isLinkDown() {
        return linkDown;
    }

    @Override
    public CompletableFuture<Void> execute(HighLevelCommand command) {
        Container container = commands.container(command);
        synchronized (linkChange) {
            // one step with the failure's report: a command either sees the link down or is ended with the others by it,
            // never admitted after that to be sent when the link is back
            if (!linkDown) {
                return actionThread.submit(container);
            }
        }
        return CompletableFuture.failedFuture(new RobotLinkException("robot '" + config.robotName()
                + "': its link is down; command '" + command.name() + "' (" + command.text() + ") was not sent", null));
    }

    @Override
    public Clock clock() {
        return config.clock();
    }

    /** Refused: this robot moves by high-level commands and has no motors to turn by degrees. */
    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        return CompletableFuture.failedFuture(new RobotException("robot '" + config.robotName() + "' on platform '" + config.platformName()
                + "' moves by its firmware's own commands; it has no motors for '" + command.name() + "' to turn"));
    }

    /**
     * Ends every running command, each with its stop.
     *
     * @return completes once those stops are written to the link and the stop no longer holds the
     *         actuators (a command submitted then is admitted as usual); fails with
     *         {@link RobotLinkException} naming the robot if the link is down or fails first, or the
     *         platform is closed. The stop is queued all the same.
     */
    @Override
    public CompletableFuture<Void> stopAll() {
        CompletableFuture<Void> handed = new CompletableFuture<>();
        if (linkDown) {
            handed.completeExceptionally(new RobotLinkException("robot '" + config.robotName()
                    + "': its stop was not written: the link is down", null));
        }
        return actionThread.submitStop(commands.stopContainer(handed), handed, e -> new RobotLinkException("robot '" + config.robotName()
                + "': its stop could not be handed to the robot: " + e.getMessage(), e));
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        Sensor sensor = sensors.get(sensorName);
        if (sensor == null) {
            return CompletableFuture.failedFuture(new IllegalArgumentException("robot '" + config.robotName() + "' has no sensor '" + sensorName + "'"));
        }
        return sensor.readRaw();
    }

    /** @throws UnsupportedOperationException always: the robot has no motors of its own */
    @Override
    public double motorDegrees(String port) {
        throw new UnsupportedOperationException("robot '" + config.robotName() + "' has no motor " + port + "; it moves by high-level commands");
    }

    @Override
    public boolean hasEncoder(String port) {
        return false;
    }

    /** Ends every command (each sends its stop), stops the action thread, then closes the link. Idempotent. */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        actionThread.close();
        if (link != null) {
            try {
                link.close();
            } catch (Exception e) {
                LOG.warn("robot '{}': closing its link: {}", config.robotName(), e.toString());
            }
        }
    }
}
