package io.robomw.platform.mavlink.gcs;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.platform.ThrottledWarnings;
import io.robomw.platform.mavlink.link.MavlinkLink;
import io.robomw.platform.mavlink.link.SerialMavlinkLink;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.MavAutopilot;
import io.robomw.platform.mavlink.wire.MavCmd;
import io.robomw.platform.mavlink.wire.MavState;
import io.robomw.platform.mavlink.wire.MavType;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.ModeFlag;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.mavlink.wire.Severity;
import io.robomw.platform.mavlink.wire.SignatureCheck;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.SocketAddress;
import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.LongSupplier;

/**
 * RoboMW as a ground station on one MAVLink link, the way ArduPilot and PX4 expect one: it sends
 * its own HEARTBEAT at 1 Hz (a GCS: type 6, autopilot 8), finds its vehicle by the vehicle's
 * HEARTBEAT (component 1, the autopilot; a given system id, or the first heard), caches what the
 * vehicle reports ({@link Telemetry}), matches COMMAND_ACKs to commands ({@link CommandSender}),
 * logs STATUSTEXTs, and ticks its listener every {@value #TICK_MILLIS} ms (20 Hz) so setpoints
 * stream while a command runs.
 *
 * <h2>A lost link</h2>
 * No HEARTBEAT from the vehicle for {@value #LINK_TIMEOUT_MILLIS} ms (MAVSDK's connection
 * timeout), or a serial port that fails, is a lost link: pending commands fail, the listener is
 * told (the platform then fails every running command, as the execution action thread's rules
 * say) and the vehicle's own failsafe acts. A serial port is reopened every second; the next
 * HEARTBEAT restores the link.
 *
 * <h2>Threads</h2>
 * One owner thread ({@code <robot>-mavlink}) receives, ticks and resends. {@link #send} and
 * {@link #command} may be called from any thread: a frame goes out at once on the caller's
 * thread (a UDP send does not block; a frame fits a serial port's buffer), so a setpoint reaches the
 * wire without a hand-over.
 */
public final class GroundStation implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(GroundStation.class);

    /** How often the listener is ticked and setpoints stream, milliseconds (20 Hz, MAVSDK's offboard rate). */
    public static final int TICK_MILLIS = 50;
    /** How long without a vehicle HEARTBEAT is a lost link, milliseconds (MAVSDK's 3 s). */
    public static final int LINK_TIMEOUT_MILLIS = 3000;
    /** The autopilot's component id (MAV_COMP_ID_AUTOPILOT1). */
    public static final int AUTOPILOT_COMPONENT = 1;
    private static final long HEARTBEAT_NANOS = 1_000_000_000L;
    private static final long REOPEN_NANOS = 1_000_000_000L;

    /** What the platform above hears. */
    public interface Listener {
        /**
         * Every tick, on the link's thread (stream setpoints, check progress).
         *
         * @param nowNanos the monotonic clock
         */
        void tick(long nowNanos);

        /**
         * The link is lost.
         *
         * @param cause what happened
         */
        void lost(RobotLinkException cause);

        /** The vehicle is heard again. */
        void restored();
    }

    private final String robot;
    private final MavlinkLink link;
    private final FrameEncoder encoder;
    private final SignatureCheck check;
    /** Frames dropped by the signature check (written by the receiver, read by the waiting caller). */
    private final AtomicLong dropped = new AtomicLong();
    private volatile SignatureCheck.Verdict lastDropped;
    private final LongSupplier nanos;
    private final int wantedSystem;
    private final Telemetry telemetry = new Telemetry();
    private final CommandSender commands;
    private final CountDownLatch found = new CountDownLatch(1);
    private final CountDownLatch positioned = new CountDownLatch(1);
    private final ThrottledWarnings warnings;
    private final FailurePolicy failures;
    private volatile Listener listener;
    private volatile VehicleKind kind;
    private volatile int vehicleSystem = -1;
    private volatile long lastVehicleHeartbeat;
    private volatile boolean lost;
    private long nextHeartbeat;
    private long nextTick;
    private long nextReopen;
    private OwnerThread thread;

    /**
     * @param robot        the robot's name, for threads and messages
     * @param link         the link (closed with this)
     * @param encoder      this ground station's identity (system 255, component 190 by default) and signer
     * @param check        checks the vehicle's signatures, or {@code null} when unsigned
     * @param wantedSystem the vehicle's system id, or 0 for the first one heard
     * @param nanos        the monotonic clock
     * @param failures     where the link's thread reports what it catches
     */
    public GroundStation(String robot, MavlinkLink link, FrameEncoder encoder, SignatureCheck check, int wantedSystem, LongSupplier nanos,
                         FailurePolicy failures) {
        this.robot = Objects.requireNonNull(robot, "robot");
        this.link = Objects.requireNonNull(link, "link");
        this.encoder = Objects.requireNonNull(encoder, "encoder");
        this.check = check;
        this.wantedSystem = wantedSystem;
        this.nanos = Objects.requireNonNull(nanos, "nanos");
        this.failures = Objects.requireNonNull(failures, "failures");
        this.commands = new CommandSender(robot, this::send, encoder.systemId(), encoder.componentId());
        this.warnings = new ThrottledWarnings(LOG, Duration.ofSeconds(5), io.robomw.api.Clock.system());
    }

    /**
     * Starts the link's thread.
     *
     * @param l who hears ticks and link changes
     * @return this
     */
    public GroundStation start(Listener l) {
        this.listener = Objects.requireNonNull(l, "listener");
        thread = OwnerThread.start(robot + "-mavlink", Thread.MAX_PRIORITY, this::round, work -> {
        }, failures);
        return this;
    }

    /**
     * Waits for the vehicle's first HEARTBEAT.
     *
     * @param within the deadline
     * @return what it is
     * @throws IOException naming the link when none came in time
     */
    public VehicleKind awaitVehicle(Duration within) throws IOException {
        try {
            if (!found.await(within.toMillis(), TimeUnit.MILLISECONDS)) {
                throw new IOException("robot '" + robot + "': no vehicle HEARTBEAT on " + link.describe() + " within " + within.toMillis()
                        + " ms" + (wantedSystem > 0 ? " from system " + wantedSystem : "")
                        + droppedSummary() + "; is the vehicle (or its telemetry radio, or SITL's --out) sending there?");
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("robot '" + robot + "': interrupted while waiting for the vehicle", e);
        }
        return kind;
    }

    /**
     * Waits for the vehicle's first local position and attitude (LOCAL_POSITION_NED and
     * ATTITUDE): a vehicle without a position fix does not send the first, and motions need both.
     *
     * @param within the deadline
     * @return whether it came in time
     */
    public boolean awaitPosition(Duration within) {
        try {
            return positioned.await(within.toMillis(), TimeUnit.MILLISECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return false;
        }
    }

    /** @return what the vehicle is (after {@link #awaitVehicle}) */
    public VehicleKind kind() {
        return kind;
    }

    /** @return the vehicle's system id, or -1 before it is found */
    public int vehicleSystem() {
        return vehicleSystem;
    }

    /** @return what it reported last */
    public Telemetry telemetry() {
        return telemetry;
    }

    /** @return whether the link is lost now */
    public boolean isLost() {
        return lost;
    }

    /** @return the monotonic clock */
    public long now() {
        return nanos.getAsLong();
    }

    /** @return the link, for messages */
    public String describe() {
        return link.describe();
    }

    /**
     * Sends a message now, on the caller's thread.
     *
     * @param p the message
     */
    public void send(Payload p) {
        try {
            link.send(encoder.encode(p));
        } catch (IOException e) {
            warnings.warn("robot '{}': sending {} on {} failed: {}", robot, p.type().name(), link.describe(), e.getMessage());
        }
    }

    /**
     * Sends a command to the vehicle's autopilot and matches its ACK (with retries).
     *
     * @param command the command
     * @param params  its params (param1..param7)
     * @return completes when ACCEPTED; fails naming the result or the timeout
     */
    public CompletableFuture<Void> command(MavCmd command, double... params) {
        int sys = vehicleSystem;
        if (sys < 0 || lost) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + robot + "': no vehicle on " + link.describe()
                    + "; " + command + " was not sent", null));
        }
        return commands.send(sys, AUTOPILOT_COMPONENT, command, nanos.getAsLong(), params);
    }

    /**
     * Switches the vehicle's mode with DO_SET_MODE (custom mode flag, and the armed flag as it is).
     *
     * @param customMode the custom mode
     * @return as {@link #command}
     */
    public CompletableFuture<Void> setMode(long customMode) {
        double[] p = kind.setModeParams(customMode);
        boolean armed = telemetry.heartbeat().map(Telemetry.Heartbeat::armed).orElse(false);
        return command(MavCmd.DO_SET_MODE, ModeFlag.CUSTOM_MODE_ENABLED.code() | (armed ? ModeFlag.SAFETY_ARMED.code() : 0), p[0], p[1]);
    }

    /** One round of the link's thread: receive for at most the time to the next tick, then tick what is due. */
    private int round() throws IOException {
        long now = nanos.getAsLong();
        int work = 0;
        if (lost && link instanceof SerialMavlinkLink serial && now >= nextReopen) {
            nextReopen = now + REOPEN_NANOS;
            try {
                serial.reopen();
            } catch (IOException e) {
                warnings.warn("robot '{}': reopening {}: {}", robot, link.describe(), e.getMessage());
                java.util.concurrent.locks.LockSupport.parkNanos(TICK_MILLIS * 1_000_000L);
                return 0;
            }
        }
        long wait = Math.max(1, (nextTick - now) / 1_000_000L);
        try {
            work += link.receive(Duration.ofMillis(Math.min(wait, TICK_MILLIS)), this::received);
        } catch (IOException e) {
            linkLost("its link " + link.describe() + " failed: " + e.getMessage(), e);
            java.util.concurrent.locks.LockSupport.parkNanos(TICK_MILLIS * 1_000_000L);
        }
        now = nanos.getAsLong();
        if (now >= nextHeartbeat) {
            nextHeartbeat = now + HEARTBEAT_NANOS;
            send(Payload.of(Messages.Heartbeat.MESSAGE)
                    .set(Messages.Heartbeat.TYPE, MavType.GCS.code())
                    .set(Messages.Heartbeat.AUTOPILOT, MavAutopilot.INVALID.code())
                    .set(Messages.Heartbeat.SYSTEM_STATUS, MavState.ACTIVE.code())
                    .set(Messages.Heartbeat.MAVLINK_VERSION, 3));
        }
        if (now >= nextTick) {
            nextTick = now + TICK_MILLIS * 1_000_000L;
            if (vehicleSystem >= 0 && !lost && now - lastVehicleHeartbeat > LINK_TIMEOUT_MILLIS * 1_000_000L) {
                linkLost("no HEARTBEAT from vehicle " + vehicleSystem + " for " + LINK_TIMEOUT_MILLIS + " ms on " + link.describe(), null);
            }
            commands.tick(now);
            if (vehicleSystem >= 0 && !lost) {
                listener.tick(now);
            }
            work++;
        }
        return work;
    }

    private void linkLost(String why, Throwable cause) {
        if (lost) {
            return;
        }
        lost = true;
        RobotLinkException e = new RobotLinkException("robot '" + robot + "': " + why, cause);
        LOG.warn("robot '{}': link lost: {}", robot, why);
        commands.failAll(e);
        listener.lost(e);
    }

    /** @return what signing dropped while no vehicle was found, for the message that says so; empty when nothing was */
    private String droppedSummary() {
        long n = dropped.get();
        return n == 0 ? "" : " (" + n + " frames dropped by signing, the last " + lastDropped
                + ": does the vehicle sign with the same passphrase as signing_key_file or signing_key_env?)";
    }

    private void received(Frame f, SocketAddress from) {
        if (check != null) {
            SignatureCheck.Verdict verdict = check.check(f);
            if (verdict != SignatureCheck.Verdict.ACCEPTED) {
                dropped.incrementAndGet();
                lastDropped = verdict;
                warnings.warn("robot '{}': dropped {} from {}: {}", robot, f, from, verdict);
                return;
            }
        }
        long now = nanos.getAsLong();
        if (vehicleSystem < 0) {
            if (!f.is(Messages.Heartbeat.MESSAGE) || f.componentId() != AUTOPILOT_COMPONENT
                    || (wantedSystem > 0 && f.systemId() != wantedSystem)
                    || f.payload().getLong(Messages.Heartbeat.TYPE) == MavType.GCS.code()) {
                return;
            }
            Payload hb = f.payload();
            kind = VehicleKind.of(hb.getLong(Messages.Heartbeat.TYPE), hb.getLong(Messages.Heartbeat.AUTOPILOT));
            vehicleSystem = f.systemId();
            lastVehicleHeartbeat = now;
            LOG.info("robot '{}': found vehicle {} on {}: {}", robot, vehicleSystem, link.describe(), kind);
            found.countDown();
        }
        if (f.systemId() != vehicleSystem) {
            return;
        }
        if (f.is(Messages.Heartbeat.MESSAGE) && f.componentId() == AUTOPILOT_COMPONENT) {
            lastVehicleHeartbeat = now;
            if (lost) {
                lost = false;
                LOG.info("robot '{}': vehicle {} heard again on {}", robot, vehicleSystem, link.describe());
                listener.restored();
            }
        }
        telemetry.update(f, now);
        if ((f.is(Messages.LocalPositionNed.MESSAGE) || f.is(Messages.Attitude.MESSAGE)) && telemetry.local().isPresent()) {
            positioned.countDown();
        }
        if (f.is(Messages.CommandAck.MESSAGE)) {
            commands.acknowledged(f.payload(), now);
        } else if (f.is(Messages.Statustext.MESSAGE)) {
            Payload p = f.payload();
            Severity s = Severity.find(p.getLong(Messages.Statustext.SEVERITY)).orElse(Severity.INFO);
            String text = p.getText(Messages.Statustext.TEXT);
            switch (s) {
                case EMERGENCY, ALERT, CRITICAL, ERROR -> LOG.error("robot '{}' says: {}", robot, text);
                case WARNING -> LOG.warn("robot '{}' says: {}", robot, text);
                case NOTICE, INFO -> LOG.info("robot '{}' says: {}", robot, text);
                case DEBUG -> LOG.debug("robot '{}' says: {}", robot, text);
            }
        }
    }

    /** Stops the link's thread and closes the link; pending commands fail. */
    @Override
    public void close() {
        if (thread != null) {
            thread.close();
        }
        link.close();
        commands.failAll(new RobotLinkException("robot '" + robot + "': the platform is closed", null));
    }
}
