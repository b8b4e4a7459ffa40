package io.robomw.sim.emulator;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;
import io.robomw.platform.ThrottledWarnings;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.PseudoTerminal;
import io.robomw.platform.link.TcpServerLink;
import io.robomw.sim.SimMotors;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A virtual brick bound to a robot in a simulated world: it answers on a serial device (a
 * pseudo-terminal it creates, so nothing has to be installed) or a TCP port exactly as the brick's
 * firmware does, and its motors and sensors are the simulated robot's.
 *
 * <h2>Two threads, one firmware state</h2>
 * The I/O thread ({@code emulator-<kind>-<robot>}, an {@link OwnerThread}) reads telegrams, delimited by the brick's
 * {@link Framing} (by default a 2-byte little-endian length, as on Bluetooth serial links), and
 * answers them from the firmware state
 * ({@link #handle}). The simulation thread calls {@link #step} after every world step: it applies
 * the firmware's motor outputs to the robot and samples its encoders and sensors into the firmware
 * state. Subclasses guard that state with one lock; physics is only touched on the simulation
 * thread.
 *
 * <p>Bad input never stops it: a zero, oversized or truncated frame is dropped with a log line and
 * counted, and the emulator goes on reading; a TCP client that leaves makes room for the next.
 *
 * <h2>Failures</h2>
 * The I/O thread hands what it catches to the simulation's {@link FailurePolicy} (a
 * {@linkplain FailurePolicy#logging() logging} one for an emulator bound to none): a telegram whose
 * handling fails is reported and dropped, and the emulator goes on; a failure of the link is
 * reported and the next telegram is awaited; a link closed under it (its delayed-link threads
 * died) ends the emulator as {@link #close()} does. A failure nothing survives ends the thread
 * cleanly: the link is closed (its driver sees it drop) and the motors stop at the next step.
 */
public abstract class BrickEmulator implements Emulator {

    private static final Logger LOG = LoggerFactory.getLogger(BrickEmulator.class);
    private static final Duration POLL = Duration.ofMillis(100);
    private static final Duration FRAME_DEADLINE = Duration.ofSeconds(1);

    private final String kind;
    private final SimMotors robot;
    private final Framing framing;
    private final AtomicLong served = new AtomicLong();
    private final AtomicLong dropped = new AtomicLong();
    /** One line a second at most about dropped input: a flood of garbage must not flood the log. */
    private final ThrottledWarnings dropWarnings = new ThrottledWarnings(LOG, Duration.ofSeconds(1), io.robomw.api.Clock.system());
    private final Runnable stepListener = this::onStep;
    private volatile boolean closed;
    private final java.util.List<Runnable> closeActions = new java.util.concurrent.CopyOnWriteArrayList<>();
    private volatile boolean running;
    private volatile Link link;
    private volatile LinkModel linkModel;
    private volatile io.robomw.sim.Simulation simulation;
    /** When the telegram being handled arrived; touched by the I/O thread only. */
    private long frameArrivalNanos;
    /** Whether the telegram being read has begun; touched by the I/O thread only. */
    private boolean frameStarted;
    private volatile OwnerThread thread;
    /** The policy the I/O thread reports to, set when it starts. */
    private volatile FailurePolicy failurePolicy;

    /**
     * @param kind     the brick, for thread names and logs ({@code nxt}, {@code ev3})
     * @param robot    the simulated robot it drives
     * @param maxFrame the longest telegram the firmware accepts, bytes after the length
     */
    protected BrickEmulator(String kind, SimMotors robot, int maxFrame) {
        this(kind, robot, Framing.lengthPrefixed(maxFrame));
    }

    /**
     * @param kind    the brick, for thread names and logs
     * @param robot   the simulated robot it drives
     * @param framing how its telegrams are delimited
     */
    protected BrickEmulator(String kind, SimMotors robot, Framing framing) {
        this.kind = kind;
        this.robot = robot;
        this.framing = framing;
    }

    /**
     * @return how slow this brick's usual link is (the emulator serves at this speed unless told
     *         otherwise); by default none
     */
    protected LinkModel defaultLinkModel() {
        return LinkModel.NONE;
    }

    /**
     * Sets how slow the emulated link is, before the emulator starts serving.
     *
     * @param model the link model; {@link LinkModel#NONE} serves as fast as the pseudo-terminal or socket goes
     * @return this
     * @throws IllegalStateException if it already serves
     */
    public synchronized BrickEmulator linkModel(LinkModel model) {
        if (thread != null) {
            throw new IllegalStateException("the " + kind + " emulator already serves on " + link.describe() + "; set its link model before it starts");
        }
        linkModel = java.util.Objects.requireNonNull(model, "model");
        return this;
    }

    /** @return how slow the emulated link is */
    public LinkModel linkModel() {
        LinkModel m = linkModel;
        return m == null ? defaultLinkModel() : m;
    }

    /**
     * Answers one telegram. Called on the I/O thread.
     *
     * @param frame the telegram without its length prefix
     * @return the reply without its length prefix, or {@code null} when none is due
     */
    protected abstract byte[] handle(byte[] frame);

    /** @return how telegrams are delimited on this emulator's link (for tests that feed it bytes as its port would) */
    Framing framing() {
        return framing;
    }

    /**
     * Applies the firmware's outputs to the robot and samples its inputs. Called on the simulation
     * thread after every world step.
     *
     * @param robot the simulated robot
     */
    protected abstract void step(SimMotors robot);

    /**
     * Stops every motor the emulator drives, as a brick that is switched off does. Called on the
     * simulation thread at the first step after {@link #close()}.
     *
     * @param robot the simulated robot
     */
    protected abstract void halt(SimMotors robot);

    private void onStep() {
        if (!closed) {
            step(robot);
            return;
        }
        halt(robot);
        for (Runnable action : closeActions) {
            action.run();
        }
        closeActions.clear();
    }

    /**
     * @return when the telegram {@link #handle} is answering arrived over the link (its last byte):
     *         a real brick acts on a telegram then, however late a loaded host lets the emulator's
     *         thread get to it. I/O thread only.
     */
    protected long frameArrivalNanos() {
        return frameArrivalNanos;
    }

    /** @return the simulated robot */
    protected SimMotors robot() {
        return robot;
    }

    /**
     * @return the wall-clock time the world step now being taken stands for (see
     *         {@code Simulation.stepWallNanos}); the time now for an emulator not bound to a simulation
     */
    protected long stepWallNanos() {
        io.robomw.sim.Simulation s = simulation;
        return s == null ? System.nanoTime() : s.stepWallNanos();
    }

    /** @return simulated seconds per wall-clock second: the real-time run's speed, 1 when not bound or not in real time */
    protected double simulatedSecondsPerSecond() {
        io.robomw.sim.Simulation s = simulation;
        return s == null ? 1 : s.realTimeSpeed();
    }

    /**
     * Makes an emulator for a robot of a simulation and steps it with the world; closing it
     * unbinds it. Each emulator's {@code bind} is this with its constructor.
     *
     * @param simulation the simulation (the robot should be one it emulates, see
     *                   {@code Simulation.load(world, names)})
     * @param robotName  the robot
     * @param emulator   makes the emulator for the robot's motors and sensors
     * @param <E>        the emulator
     * @return the emulator, not yet serving
     * @throws IllegalArgumentException if the world has no such robot
     */
    protected static <E extends BrickEmulator> E bind(io.robomw.sim.Simulation simulation, String robotName,
                                                      java.util.function.Function<SimMotors, E> emulator) {
        SimMotors motors = SimMotors.of(simulation.world(), robotName).orElseThrow(() -> new IllegalArgumentException(
                "world '" + simulation.world().description().name() + "' has no robot '" + robotName + "'"));
        E e = emulator.apply(motors);
        ((BrickEmulator) e).simulation = simulation;
        simulation.addStepListener(e.stepListener());
        e.onClose(() -> simulation.removeStepListener(e.stepListener()));
        return e;
    }

    /** @return the listener to add to the simulation ({@code Simulation.addStepListener}); always the same one */
    public Runnable stepListener() {
        return stepListener;
    }

    /**
     * Creates a pseudo-terminal and serves on it.
     *
     * @return the device path a driver opens, for example {@code /dev/pts/5}
     * @throws IOException if no pseudo-terminal can be made
     */
    @Override
    public String startOnPseudoTerminal() throws IOException {
        PseudoTerminal pty = PseudoTerminal.open();
        start(new PseudoTerminalLink(pty));
        return pty.devicePath();
    }

    /**
     * Serves on a TCP port, one client at a time.
     *
     * @param bindAddress the address to listen on (127.0.0.1 for tests)
     * @param port        the port, 0 for any free one
     * @return the port it listens on
     * @throws IOException if it cannot listen
     */
    @Override
    public int startOnTcp(String bindAddress, int port) throws IOException {
        TcpServerLink server = new TcpServerLink(bindAddress, port);
        server.open();
        start(server);
        return server.localPort();
    }

    private synchronized void start(Link endpoint) {
        if (thread != null) {
            endpoint.close();
            throw new IllegalStateException("the " + kind + " emulator of '" + robot.robot().name() + "' is already serving on " + link.describe());
        }
        LinkModel model = linkModel();
        FailurePolicy failures = failures();
        failurePolicy = failures;
        link = model.isNone() ? endpoint : new DelayedLink(endpoint, model, failures);
        running = true;
        thread = OwnerThread.start(role(), Thread.NORM_PRIORITY, new Serving(), EmulatorThreads.BACK_OFF, failures);
        LOG.info("{} emulator for '{}' serving on {}", kind, robot.robot().name(), link.describe());
    }

    /** @return the I/O thread's name, which its failures are reported under */
    private String role() {
        return "emulator-" + kind + "-" + robot.robot().name();
    }

    /** @return the policy the emulator's threads report to: its simulation's, or a logging one */
    protected FailurePolicy failures() {
        io.robomw.sim.Simulation s = simulation;
        return s == null ? FailurePolicy.logging() : s.failures();
    }

    /** The I/O thread's duty: a telegram a round; dying, it stops serving as {@link #close()} does. */
    private final class Serving implements OwnerThread.Duty {
        @Override
        public int doWork() throws IOException {
            return serveOne();
        }

        @Override
        public void onDeath(Throwable failure) {
            closed = true;
            running = false;
            Link l = link;
            if (l != null) {
                l.close(); // the driver sees the link drop; the motors stop at the next step
            }
        }
    }

    /** The reader {@link #framing} reads a telegram with: its first byte for a poll interval, the rest within the frame deadline. */
    private final Framing.Reader reader = n -> {
        byte[] buf = new byte[n];
        return readFully(buf, 0, n, frameStarted ? FRAME_DEADLINE : null) ? buf : null;
    };

    /**
     * One round of the I/O thread: reads a telegram (waiting at most a poll interval for its first
     * byte) and answers it.
     *
     * @return 1 (a telegram was answered or dropped, or the poll interval passed); 0 once the
     *         emulator stopped (the round ends the loop)
     * @throws IOException if the link failed (reported; the next round reads on)
     */
    private int serveOne() throws IOException {
        if (!running) {
            OwnerThread t = thread;
            if (t != null) {
                t.close(); // on its own thread: ends the loop after this round
            }
            return 0;
        }
        try {
            frameStarted = false;
            byte[] frame;
            try {
                frame = framing.read(reader);
            } catch (Framing.MalformedFrameException e) {
                drop(e.getMessage());
                drain();
                return 1;
            }
            if (frame == null) {
                if (frameStarted && running) {
                    drop("truncated telegram: its bytes did not all arrive within " + FRAME_DEADLINE.toMillis() + " ms");
                }
                return 1;
            }
            Link l = link;
            frameArrivalNanos = l instanceof DelayedLink d ? d.lastDeliveredAt() : System.nanoTime();
            byte[] reply;
            try {
                reply = handle(frame);
            } catch (Throwable e) {
                failurePolicy.surviveOrRethrow(role() + ": telegram " + hex(frame), e);
                drop("telegram " + hex(frame) + " could not be handled: " + e);
                return 1;
            }
            served.incrementAndGet();
            if (reply != null) {
                byte[] out = framing.encode(reply);
                link.write(out, 0, out.length);
            }
        } catch (LinkLostException e) {
            if (running) {
                LOG.info("{} emulator for '{}': peer left ({}); waiting for the next", kind, robot.robot().name(), e.getMessage());
            }
        } catch (IOException e) {
            if (!running) {
                return 1;
            }
            if (!link.isOpen()) {
                LOG.warn("{} emulator for '{}': its link {} was closed under it ({}); the emulator stops", kind, robot.robot().name(),
                        link.describe(), e.getMessage());
                closed = true;
                running = false;
                return 1;
            }
            throw e;
        }
        return 1;
    }

    /**
     * Reads exactly n bytes.
     *
     * @param deadline for the whole read, or {@code null} to wait one poll interval for the first
     *                 byte (then the frame deadline applies)
     * @return false if the deadline passed, or the emulator stopped, before n bytes came
     */
    private boolean readFully(byte[] buf, int off, int n, Duration deadline) throws IOException {
        long end = System.nanoTime() + (deadline == null ? POLL : deadline).toNanos();
        int got = 0;
        while (got < n && running) {
            if (System.nanoTime() > end) {
                return false;
            }
            int r = link.read(buf, off + got, n - got, POLL);
            if (r > 0 && !frameStarted) {
                frameStarted = true;
                end = System.nanoTime() + FRAME_DEADLINE.toNanos();
            }
            got += Math.max(0, r);
        }
        return got == n;
    }

    private void drain() throws IOException {
        byte[] junk = new byte[256];
        while (running && link.read(junk, 0, junk.length, Duration.ofMillis(20)) > 0) {
            // discard until the line is quiet, so the next frame starts clean
        }
    }

    private void drop(String why) {
        long n = dropped.incrementAndGet();
        dropWarnings.warn("{} emulator for '{}': dropped input ({} so far): {}", kind, robot.robot().name(), n, why);
    }

    /** @return telegrams answered */
    public long framesServed() {
        return served.get();
    }

    /** @return malformed or unhandled input dropped */
    public long framesDropped() {
        return dropped.get();
    }

    /** @return where it serves, for messages */
    @Override
    public String describe() {
        Link l = link;
        return l == null ? kind + " emulator (not serving)" : kind + " emulator on " + l.describe();
    }

    /**
     * @param bytes bytes
     * @return them in hex, for logs
     */
    protected static String hex(byte[] bytes) {
        StringBuilder sb = new StringBuilder();
        for (byte b : bytes) {
            sb.append(String.format("%02X ", b & 0xFF));
        }
        return sb.toString().trim();
    }

    /**
     * @param action run on the simulation thread at the first step after the emulator closed, once
     *               its motors are stopped (unbinding it from its simulation)
     */
    public void onClose(Runnable action) {
        closeActions.add(action);
    }

    /**
     * Stops serving and closes the device or port; a driver on it sees the link drop. At the next
     * world step its motors stop and it unbinds from the simulation.
     */
    @Override
    public synchronized void close() {
        closed = true;
        running = false;
        Link l = link;
        if (l != null) {
            l.close();
        }
        OwnerThread t = thread;
        if (t != null) {
            t.close();
        }
    }
}
