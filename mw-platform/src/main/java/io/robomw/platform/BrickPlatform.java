package io.robomw.platform;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.api.spi.SensorChannel;
import io.robomw.api.SensorType;
import io.robomw.api.ReturnType;
import io.robomw.platform.exec.ExecutionActionThread;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.locks.LockSupport;

/**
 * A running robot platform assembled from the Platform Layer's parts: an
 * {@link ExecutionActionThread}, a driver's {@link GenericMotorPlatform} and
 * {@link SensorPlatform}, and the link they talk over. Drivers' {@code PlatformProvider}s build one
 * of these; the Configuration Layer sees only {@link RobotPlatform}.
 *
 * <p>With the wall clock, {@link #start()} starts the action thread and (for
 * {@link LinkThreading#OWN_THREAD}) a link thread named {@code <robot>-link} that services the
 * motor link once per cycle. A link failure is reported to the action thread, which stops every
 * command; the link thread keeps trying, so a driver that reopens its link in {@code runImpl} or
 * {@code pollFeedback} recovers by itself.
 *
 * <p><b>The link thread never dies silently.</b> What the driver throws besides an I/O failure (an
 * exception, or an error it can cause: {@link LinkageError}, {@link AssertionError},
 * {@link StackOverflowError}) is counted and logged, and the loop goes on. Anything else ends the
 * thread: it is logged, every command is stopped (a safety stop through the action thread, handed
 * to the link by this thread before it exits), and the robot is marked failed: later commands fail
 * saying why. {@link #close()} waits until the link thread has really ended.
 */
public final class BrickPlatform implements RobotPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(BrickPlatform.class);

    private final PlatformConfig config;
    private final ExecutionActionThread actionThread;
    private final GenericMotorPlatform motors;
    private final Map<String, Sensor> sensors = new LinkedHashMap<>();
    private final LinkThreading threading;
    private final AutoCloseable link;
    private volatile boolean running;
    private volatile boolean linkDown;
    private final java.util.concurrent.atomic.AtomicLong driverErrors = new java.util.concurrent.atomic.AtomicLong();
    private Thread linkThread;
    /** Why the link thread died, once it has. */
    private volatile RobotLinkException linkThreadFailure;
    private final ThrottledWarnings refusals;

    /**
     * Creates every sensor of the description.
     *
     * @param config        the platform's configuration
     * @param motors        the driver's motor platform
     * @param sensorPlatform the driver's sensor platform
     * @param threading     where the link side runs
     * @param link          closed last, or {@code null}
     * @throws IOException if a sensor cannot be set up
     */
    public BrickPlatform(PlatformConfig config, GenericMotorPlatform motors, SensorPlatform sensorPlatform,
                         LinkThreading threading, AutoCloseable link) throws IOException {
        this.config = config;
        this.refusals = new ThrottledWarnings(LOG, java.time.Duration.ofSeconds(1), config.clock());
        this.motors = motors;
        this.threading = threading;
        this.link = link;
        this.actionThread = new ExecutionActionThread(config.robotName(), config.clock(), config.cyclePeriod(), config.failures());
        motors.cyclePeriod(config.cyclePeriod());
        if (threading == LinkThreading.INLINE) {
            motors.linkServicedInline();
        }
        for (SensorChannel channel : config.sensors()) {
            Sensor sensor = channel.type() == SensorType.TACHO
                    ? sensorPlatform.selectMotorSensor(channel.port(), channel.type(), ReturnType.RAW)
                    : sensorPlatform.createSensor(channel);
            sensors.put(channel.name(), sensor);
        }
        actionThread.addCycleListener(this::afterCycle);
    }

    /** @return the execution action thread, which a simulation cycles itself */
    public ExecutionActionThread actionThread() {
        return actionThread;
    }

    /** @return the motor platform */
    public GenericMotorPlatform motors() {
        return motors;
    }

    /**
     * Starts the threads, if the clock is the wall clock; a simulation cycles a platform on a
     * simulated clock itself.
     *
     * @return this
     */
    public BrickPlatform start() {
        if (config.cycling() == Cycling.BY_OWNER) {
            return this;
        }
        running = true;
        if (threading == LinkThreading.OWN_THREAD) {
            linkThread = new Thread(this::linkLoop, config.robotName() + "-link");
            linkThread.setDaemon(true);
            linkThread.start();
        }
        actionThread.start();
        return this;
    }

    private void afterCycle() {
        // A listener runs before the cycle is counted: this is cycle cycles() + 1.
        boolean changed = motors.flushOutputs(actionThread.cycles() + 1);
        if (threading == LinkThreading.INLINE) {
            serviceLink();
        } else if (changed && linkThread != null) {
            LockSupport.unpark(linkThread);
        }
    }

    /**
     * Services the link once a cycle: a service that took part of the cycle (a slow link's round
     * trip) waits only for the rest of it, so readings come as often as the link allows.
     */
    private void linkLoop() {
        try {
            serviceLoop();
        } catch (Throwable t) {
            linkThreadDied(t);
        }
    }

    /**
     * The link thread cannot go on: stops every command, hands the stop to the link one last time,
     * and marks the robot failed. Runs on the dying thread; must not throw.
     */
    private void linkThreadDied(Throwable t) {
        driverErrors.incrementAndGet();
        RobotLinkException why = new RobotLinkException("robot '" + config.robotName() + "': its link thread died of " + t
                + "; every command was stopped", t);
        linkThreadFailure = why;
        try {
            LOG.error("robot '{}': the link thread died; stopping every command and marking the robot failed", config.robotName(), t);
            actionThread.linkFailed(config.platformName(), t);
            // The last stop: a safety stop through the action thread, then handed to the link from here.
            actionThread.submit(motors.stopContainer()).get(10 * config.cyclePeriod().toNanos() + 1_000_000_000L,
                    java.util.concurrent.TimeUnit.NANOSECONDS);
        } catch (Throwable e) {
            // the action thread is gone too, or the stop timed out: hand over what it published
        }
        try {
            motors.flushOutputs();
            motors.serviceLink();
        } catch (Throwable e) {
            LOG.error("robot '{}': the last stop could not be handed to the link: {}", config.robotName(), e.toString());
        }
    }

    private void serviceLoop() {
        long period = config.cyclePeriod().toNanos();
        while (running) {
            long started = BrickChannel.LINK_TIME.nanoTime(); // the link is paced in real time, whatever clock the robot runs on
            serviceLink();
            long rest = (linkDown ? period * 10 : period) - (BrickChannel.LINK_TIME.nanoTime() - started);
            if (rest > 0) {
                LockSupport.parkNanos(this, rest);
            }
        }
    }

    private void serviceLink() {
        // Containers admitted in cycles up to this one were running before the service began.
        long began = actionThread.cycles();
        try {
            motors.serviceLink();
            if (linkDown) {
                linkDown = false;
                LOG.info("robot '{}': link restored", config.robotName());
            }
        } catch (io.robomw.platform.brick.ChannelBusyException e) {
            // A sensor read held the channel too long: nothing is known to be wrong with the link.
            // The states taken were put back and go with the next service.
            LOG.debug("robot '{}': {}", config.robotName(), e.getMessage());
        } catch (IOException e) {
            if (!linkDown) {
                linkDown = true;
                LOG.warn("robot '{}': link failed: {}", config.robotName(), e.getMessage());
                actionThread.linkFailed(config.platformName(), e);
            }
            motors.failPendingStops(linkDown("failed: " + e.getMessage(), e));
        } catch (Throwable t) {
            // The brick answered but refused (an error status), or the driver failed: the link is fine.
            // The commands running now fail with the brick's own words, at once: those whose states
            // the service took and those running when it began, not those admitted since (a poll
            // refused just before the brick recovered must not fail them). The log gets one line a
            // second at most about refusals (the stack trace at debug level); the driver's own
            // failures go to the failure policy. One the thread cannot survive ends it (linkThreadDied).
            if (!FailurePolicy.survivable(t)) {
                throw (VirtualMachineError) t;
            }
            driverErrors.incrementAndGet();
            actionThread.driverFailed(t instanceof RuntimeException r ? r
                    : new RobotException("robot '" + config.robotName() + "': the driver failed: " + t, t),
                    Math.max(began, motors.servedCycle()));
            if (t instanceof RobotException) {
                refusals.warn("{}", t.getMessage());
                LOG.debug("robot '{}': the driver's refusal", config.robotName(), t);
            } else {
                config.failures().survived(config.robotName() + "-link", t);
            }
        }
    }

    /** Joins the link thread until it has really ended, interrupting a service blocked on its link (as the action thread's close does). */
    private void awaitEnd(Thread t) {
        boolean interrupted = false;
        while (t.isAlive()) {
            LockSupport.unpark(t);
            try {
                t.join(1_000);
            } catch (InterruptedException e) {
                interrupted = true;
            }
            if (t.isAlive()) {
                LOG.warn("robot '{}': waiting for its link thread to end; interrupting it", config.robotName());
                t.interrupt();
            }
        }
        if (interrupted) {
            Thread.currentThread().interrupt();
        }
    }

    /** @return why the link thread died, if it did */
    public java.util.Optional<RobotLinkException> linkThreadFailure() {
        return java.util.Optional.ofNullable(linkThreadFailure);
    }

    /** @return how many times the driver's runImpl or pollFeedback threw something other than an I/O failure */
    public long driverErrors() {
        return driverErrors.get();
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        RobotLinkException failed = linkThreadFailure;
        if (failed != null) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + config.robotName() + "' has failed: " + failed.getMessage()
                    + "; command '" + command.name() + "' was not run (close the robot and open it again)", failed));
        }
        if (linkDown) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + config.robotName()
                    + "': its link is down; command '" + command.name() + "' was not run", null));
        }
        return actionThread.submit(motors.container(command));
    }

    /**
     * Runs a command nobody waits for: a {@code drive} (every target continuous) goes through the
     * motor platform's refresh slot instead of a container per call ({@link GenericMotorPlatform#submitDetached}),
     * in its place among the other commands; when the link is down or its thread has failed, it is
     * refused as {@link #run} refuses it.
     */
    @Override
    public void runDetached(MotorCommand command) {
        if (linkThreadFailure != null || linkDown) {
            run(command); // a failed future, dropped: nobody waits for it
            return;
        }
        motors.submitDetached(command, actionThread);
    }

    /**
     * Stops every motor: a safety-priority container brakes them all in the next cycle.
     *
     * @return completes once the link side has written the batch carrying the brakes (with the
     *         platform's own threads, on its link thread; inline, within the cycle that applied the
     *         stop); fails with {@link RobotLinkException} naming the robot if the link is down or
     *         fails before, or the platform has failed or is closed. The stop is queued all the same:
     *         a link that comes back brakes the motors first.
     */
    @Override
    public CompletableFuture<Void> stopAll() {
        CompletableFuture<Void> handed = new CompletableFuture<>();
        RobotLinkException failed = linkThreadFailure;
        if (failed != null) {
            handed.completeExceptionally(new RobotLinkException("robot '" + config.robotName() + "' has failed: " + failed.getMessage()
                    + "; its stop could not be handed to the hardware (close the robot and open it again)", failed));
        } else if (linkDown) {
            handed.completeExceptionally(linkDown("it is down", null));
        }
        actionThread.submit(motors.stopContainer(handed)).whenComplete((v, e) -> {
            if (e != null && !(e instanceof io.robomw.api.CommandPreemptedException)) {
                // Refused by a failed or closed action thread (a newer stop that took over hands itself over).
                handed.completeExceptionally(new RobotLinkException("robot '" + config.robotName() + "': its stop could not be handed to the hardware: "
                        + e.getMessage(), e));
            }
        });
        return handed;
    }

    private RobotLinkException linkDown(String why, Throwable cause) {
        return new RobotLinkException("robot '" + config.robotName() + "': its stop was not handed to the hardware: the link ("
                + config.platformName() + ") " + why + "; it goes out when the link returns", cause);
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        Sensor sensor = sensors.get(sensorName);
        if (sensor == null) {
            return CompletableFuture.failedFuture(new IllegalArgumentException("robot '" + config.robotName() + "' has no sensor '" + sensorName + "'"));
        }
        return sensor.readRaw();
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
     * Stops every motor, hands the stop to the hardware, stops the threads, leaves every output
     * idle (coasting, as the bricks' own tools do when a program stops) and closes the link.
     */
    @Override
    public void close() {
        running = false;
        actionThread.close();
        if (linkThread != null) {
            awaitEnd(linkThread);
        }
        motors.flushOutputs();
        if (!linkDown) {
            serviceLink();
        }
        motors.coastAll();
        if (!linkDown) {
            serviceLink();
        }
        motors.failPendingStops(linkDown("was closed with the robot", null));
        if (link != null) {
            try {
                link.close();
            } catch (Exception e) {
                LOG.warn("robot '{}': closing its link: {}", config.robotName(), e.toString());
            }
        }
    }
}
