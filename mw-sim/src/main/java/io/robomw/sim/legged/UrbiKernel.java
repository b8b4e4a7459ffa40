package io.robomw.sim.legged;

import io.robomw.sim.legged.UrbiParser.Assign;
import io.robomw.sim.legged.UrbiParser.Binary;
import io.robomw.sim.legged.UrbiParser.Block;
import io.robomw.sim.legged.UrbiParser.Call;
import io.robomw.sim.legged.UrbiParser.Evaluate;
import io.robomw.sim.legged.UrbiParser.Every;
import io.robomw.sim.legged.UrbiParser.Expr;
import io.robomw.sim.legged.UrbiParser.Keyword;
import io.robomw.sim.legged.UrbiParser.Loop;
import io.robomw.sim.legged.UrbiParser.Neg;
import io.robomw.sim.legged.UrbiParser.Num;
import io.robomw.sim.legged.UrbiParser.Ref;
import io.robomw.sim.legged.UrbiParser.Statement;
import io.robomw.sim.legged.UrbiParser.Stop;
import io.robomw.sim.legged.UrbiParser.Str;

import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;
import java.util.Locale;
import java.util.OptionalDouble;
import java.util.Queue;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.LongSupplier;

/**
 * The emulated Aibo's URBI server core: runs the statements of its sessions (network clients of
 * the emulator, or the simulator's own platform) against a {@link Quadruped} and the dog's
 * sensors, and reports what they print, their errors and their ends.
 *
 * <h2>What it answers</h2>
 * <ul>
 *   <li>{@code robot.walk(d, v)}, {@code robot.turn(a, w)}, {@code robot.arc(r, a, v)}: walk,
 *   returning when done (metres, radians, m/s, rad/s; positive turns left); {@code robot.drive(v, w)}:
 *   walk on until replaced, stopped, or not repeated within {@code robot.watchdogInterval} seconds;
 *   {@code robot.stop()}; postures {@code robot.sit()}, {@code robot.stand()}, {@code robot.lie()};
 *   {@code robot.kick()}. A new walking call ends the one before, which returns (its end is
 *   reported). Speeds above the gait's limits, or walking with the motors off, are errors.</li>
 *   <li>Devices, by their Aibo names: joints ({@code legLF1} ... {@code legRH3}, {@code neck},
 *   {@code headPan}, {@code headTilt}, {@code tailPan}, {@code tailTilt}, {@code mouth}) are read
 *   and set in degrees ({@code headPan.val = 30 time:1000}, {@code speed:} in degrees per second);
 *   sensors are read-only: {@code distanceNear}, {@code distanceFar}, {@code distanceChest}
 *   (millimetres), {@code accelX/Y/Z} (m/s², x forward, y left, z up), paws {@code pawLF},
 *   {@code pawLH}, {@code pawRF}, {@code pawRH}, {@code headSensor}, {@code chinSensor},
 *   {@code backSensorF/M/R} (1 pressed, 0 not).</li>
 *   <li>Variables {@code robot.watchdogInterval} (read, write), {@code robot.maxSpeed} and
 *   {@code robot.maxTurnRate} (read).</li>
 *   <li>{@code motoron}/{@code motoroff} (also {@code motors on/off}), {@code ping},
 *   {@code stop tag}, blocks, {@code every(period)}, {@code loop}, arithmetic on numbers.</li>
 * </ul>
 * A statement ended by {@code ;} or {@code |} holds the statements after it until it ends; one
 * ended by {@code ,} or {@code &amp;} runs in the background. Messages carry the tag of the
 * statement that caused them (an inner statement without a tag takes its outer one's); a statement
 * tagged with the flag {@code +end} reports {@code *** end} when it ends, however it ends.
 *
 * <h2>Bad input</h2>
 * A statement that cannot be parsed, or that fails, is answered with {@code !!!} and its tag (when
 * it could be read), and the session goes on. A session may have at most {@value #MAX_PENDING}
 * statements waiting and {@value #MAX_JOBS} running, counting those inside blocks, loops and
 * {@code every}s: a statement beyond that is refused with an error (but {@code stop} and the
 * keywords, which end as they begin), and a loop or an {@code every} skips its turns until some
 * end (so nested loops cannot multiply without bound); a client that
 * sends more between two steps than the queue holds loses the excess, told by one error at the
 * next step.
 *
 * <h2>Threads</h2>
 * {@link Session#submit} may be called from any thread (a client's reader); it only parses and
 * queues. Everything else runs in {@link #step}, on the thread that steps the dog.
 */
public final class UrbiKernel {

    /** Statements a session may have waiting. */
    public static final int MAX_PENDING = 1024;
    /** Jobs a session may have running, nested ones included. */
    public static final int MAX_JOBS = 256;
    /** How long {@code robot.sit()} takes, seconds. */
    public static final double SIT_SECONDS = 1.5;
    /** How long {@code robot.stand()} takes, seconds. */
    public static final double STAND_SECONDS = 1.5;
    /** How long {@code robot.lie()} takes, seconds. */
    public static final double LIE_SECONDS = 2.0;
    /** How long {@code robot.kick()} takes, seconds. */
    public static final double KICK_SECONDS = 1.0;
    /** {@code robot.watchdogInterval} when nobody set it, seconds. */
    public static final double DEFAULT_WATCHDOG_SECONDS = 1.0;

    /** What a message is. */
    public enum Kind {
        /** A value. */
        VALUE,
        /** {@code ***}. */
        SYSTEM,
        /** {@code !!!}. */
        ERROR
    }

    /** Where a session's messages go. */
    @FunctionalInterface
    public interface Sink {
        /**
         * @param timestampMillis the server's clock
         * @param tag             the tag, or ""
         * @param kind            what it is
         * @param text            the payload without its prefix
         */
        void message(long timestampMillis, String tag, Kind kind, String text);
    }

    /** The dog's sensor devices. */
    @FunctionalInterface
    public interface Sensors {
        /**
         * @param device a device name ({@code distanceNear}, {@code accelX}, {@code pawLF})
         * @return its value in its own unit, or empty if the dog has no such sensor
         */
        OptionalDouble read(String device);
    }

    private final String robot;
    private final Quadruped dog;
    private final Sensors sensors;
    private final LongSupplier nanos;
    private final io.robomw.api.spi.FailurePolicy failures;
    private final long startNanos;
    private final List<Session> sessions = new CopyOnWriteArrayList<>();
    private boolean motorsOn;

    /**
     * @param robot   the robot's name, for logs
     * @param dog     the gait and joints
     * @param sensors the sensor devices
     * @param nanos   the server's clock (the world's)
     */
    public UrbiKernel(String robot, Quadruped dog, Sensors sensors, LongSupplier nanos) {
        this(robot, dog, sensors, nanos, io.robomw.api.spi.FailurePolicy.logging());
    }

    /**
     * @param robot    the robot's name, for logs
     * @param dog      the gait and joints
     * @param sensors  the sensor devices
     * @param nanos    the server's clock (the world's)
     * @param failures where a session's failure in a step is reported (the session is closed)
     */
    public UrbiKernel(String robot, Quadruped dog, Sensors sensors, LongSupplier nanos, io.robomw.api.spi.FailurePolicy failures) {
        this.failures = java.util.Objects.requireNonNull(failures, "failures");
        this.robot = robot;
        this.dog = dog;
        this.sensors = sensors;
        this.nanos = nanos;
        this.startNanos = nanos.getAsLong();
        dog.watchdogInterval(DEFAULT_WATCHDOG_SECONDS);
    }

    /**
     * Opens a session.
     *
     * @param name for logs
     * @param sink where its messages go (called on the stepping thread, and by {@link Session#submit}
     *             for a statement it cannot parse)
     * @return the session
     */
    public Session open(String name, Sink sink) {
        Session s = new Session(name, sink);
        sessions.add(s);
        return s;
    }

    /** @return whether the motors are on */
    public boolean motorsOn() {
        return motorsOn;
    }

    /** Switches the motors on, as {@code motoron} does (for a session that sends no startup). */
    public void switchMotorsOn() {
        motorsOn = true;
    }

    /** @return the server's clock, milliseconds since it started */
    public long millis() {
        return (nanos.getAsLong() - startNanos) / 1_000_000;
    }

    /**
     * Runs one step: every session's queued statements start (unless held by a sequential one)
     * and every running job advances. On the thread that steps the dog. What a session's step
     * throws concerns that session: if survivable, it is reported to the failure policy, the
     * client is told, and the session is closed (its jobs stop); otherwise it ends the step.
     */
    public void step() {
        for (Session s : sessions) {
            try {
                s.step();
            } catch (Throwable e) {
                failures.surviveOrRethrow("urbi-" + robot + ": " + s.name, e);
                s.emit("", Kind.ERROR, "internal error: " + e + "; this session is closed");
                s.close();
            }
        }
    }

    /** Ends every session's jobs (the emulator was switched off). */
    public void stopAll() {
        for (Session s : sessions) {
            s.close();
            s.step();
        }
        dog.stop();
    }

    // ---- sessions ----

    /** One client of the server. */
    public final class Session {
        private final String name;
        private final Sink sink;
        private final UrbiStatementSplitter splitter = new UrbiStatementSplitter();
        private final Queue<Object> inbound = new ConcurrentLinkedQueue<>();
        /** How many statements {@link #inbound} holds: a client sending faster than the steps take them loses the excess. */
        private final java.util.concurrent.atomic.AtomicInteger inboundSize = new java.util.concurrent.atomic.AtomicInteger();
        private final java.util.concurrent.atomic.AtomicLong dropped = new java.util.concurrent.atomic.AtomicLong();
        private final Deque<Object> pending = new ArrayDeque<>();
        private final List<Job> running = new ArrayList<>();
        private Job blocking;
        /** Jobs of this session begun and not ended, nested ones included; on the stepping thread. */
        private int jobs;
        private volatile boolean closed;
        private boolean stopped;

        private Session(String name, Sink sink) {
            this.name = name;
            this.sink = sink;
        }

        /**
         * Cuts and parses what a client sent and queues it for the next step. Any thread, one at a
         * time per session.
         *
         * @param bytes the bytes
         * @param off   the first
         * @param len   how many
         */
        public void submit(byte[] bytes, int off, int len) {
            splitter.feed(bytes, off, len, new UrbiStatementSplitter.Listener() {
                @Override
                public void statement(String text, char terminator) {
                    if (full()) {
                        return;
                    }
                    try {
                        queue(UrbiParser.parse(text, terminator));
                    } catch (UrbiParser.UrbiSyntaxException e) {
                        queue(new Refused(e.tag(), e.getMessage()));
                    }
                }

                @Override
                public void error(String message) {
                    if (!full()) {
                        queue(new Refused("", "syntax error: " + message));
                    }
                }
            });
        }

        /** @return whether the statements waiting for the next step fill the queue; if so this one is dropped and counted */
        private boolean full() {
            if (inboundSize.get() >= MAX_PENDING) {
                dropped.incrementAndGet();
                return true;
            }
            return false;
        }

        private void queue(Object statementOrRefusal) {
            inboundSize.incrementAndGet();
            inbound.add(statementOrRefusal);
        }

        /**
         * @param text URBI text, whole statements with their terminators
         */
        public void submit(String text) {
            byte[] b = text.getBytes(java.nio.charset.StandardCharsets.ISO_8859_1);
            submit(b, 0, b.length);
        }

        /** @return whether a sequential statement still runs and holds the statements after it (the client's own doing); on the stepping thread */
        boolean holding() {
            return blocking != null;
        }

        /** @return whether what the client sent so far ends inside a statement, a comment or a binary value's bytes */
        boolean midStatement() {
            return splitter.midStatement();
        }

        /** @return the session's jobs begun and not ended, nested ones included; on the stepping thread */
        int jobs() {
            return jobs;
        }

        /**
         * @param st a statement about to begin
         * @return whether it may: fewer than {@value UrbiKernel#MAX_JOBS} jobs run, or it ends as it
         *         begins ({@code stop}, so a client can always end what runs, and the keywords)
         */
        private boolean roomFor(Statement st) {
            return jobs < MAX_JOBS || st.command() instanceof Stop || st.command() instanceof Keyword;
        }

        /** Ends the session: its jobs stop at the next step, and it is forgotten. */
        public void close() {
            closed = true;
        }

        /** @return whether it was closed */
        public boolean isClosed() {
            return closed;
        }

        void emit(String tag, Kind kind, String text) {
            if (stopped) {
                return;
            }
            sink.message(millis(), tag, kind, text);
        }

        private void step() {
            if (closed) {
                if (!stopped) {
                    for (Job j : List.copyOf(running)) {
                        j.stop();
                    }
                    stopped = true;
                    running.clear();
                    pending.clear();
                    inbound.clear();
                    inboundSize.set(0);
                    blocking = null;
                    sessions.remove(this);
                }
                return;
            }
            for (Object o; (o = inbound.poll()) != null; ) {
                inboundSize.decrementAndGet();
                if (pending.size() >= MAX_PENDING) {
                    String tag = o instanceof Statement st ? st.tag() : ((Refused) o).tag();
                    emit(tag, Kind.ERROR, "too many commands waiting (" + MAX_PENDING + "); this one was dropped");
                } else {
                    pending.add(o);
                }
            }
            long lost = dropped.getAndSet(0);
            if (lost > 0) {
                emit("", Kind.ERROR, "too many commands waiting (" + MAX_PENDING + "); " + lost + " dropped");
            }
            boolean advanced = false;
            do {
                while (blocking == null && !pending.isEmpty()) {
                    Object next = pending.poll();
                    if (next instanceof Refused r) {
                        emit(r.tag(), Kind.ERROR, r.message());
                        continue;
                    }
                    Statement st = (Statement) next;
                    if (!roomFor(st)) {
                        emit(st.tag(), Kind.ERROR, TOO_MANY_JOBS);
                        continue;
                    }
                    Job job = start(this, st, "");
                    if (!job.done) {
                        running.add(job);
                        if (st.sequential()) {
                            blocking = job;
                        }
                    }
                }
                if (!advanced) {
                    for (Job j : List.copyOf(running)) {
                        if (!j.done) {
                            j.advance();
                        }
                    }
                    advanced = true;
                }
                running.removeIf(j -> j.done);
                if (blocking != null && blocking.done) {
                    blocking = null;
                }
            } while (blocking == null && !pending.isEmpty());
        }

        private void stopTag(String tag) {
            for (Job j : List.copyOf(running)) {
                j.stopTagged(tag);
            }
        }
    }

    /** The error of a statement refused because its session runs {@value #MAX_JOBS} jobs. */
    static final String TOO_MANY_JOBS = "too many commands running (" + MAX_JOBS + "); stop some first";

    /** A statement that could not be parsed, with its tag if it was read. */
    private record Refused(String tag, String message) {
    }

    // ---- jobs ----

    /** Starts a statement: its job has run its first part (and may be done already). */
    private Job start(Session session, Statement st, String outerTag) {
        String tag = st.tag().isEmpty() ? outerTag : st.tag();
        Job job = new Job(session, st, tag);
        job.begin();
        return job;
    }

    /** One running statement. */
    private final class Job {
        private final Session session;
        private final Statement statement;
        private final String tag;
        private final List<Job> children = new ArrayList<>();
        private boolean done;
        private Quadruped.Motion motion;
        private int next;
        private Job waiting;
        private double period;
        private long nextAt;

        Job(Session session, Statement statement, String tag) {
            this.session = session;
            this.statement = statement;
            this.tag = tag;
            session.jobs++;
        }

        void begin() {
            try {
                UrbiParser.Command c = statement.command();
                if (c instanceof Block) {
                    advanceBlock();
                } else if (c instanceof Stop s) {
                    session.stopTag(s.tag());
                    finish();
                } else if (c instanceof Every e) {
                    period = e.periodSeconds();
                    nextAt = nanos.getAsLong();
                    advanceRepeat(e.body());
                } else if (c instanceof Loop l) {
                    period = 0;
                    nextAt = nanos.getAsLong();
                    advanceRepeat(l.body());
                } else if (c instanceof Keyword k) {
                    keyword(k.word());
                    finish();
                } else if (c instanceof Assign a) {
                    assign(a);
                } else if (c instanceof Evaluate e) {
                    evaluate(e.expr());
                }
            } catch (UrbiError e) {
                fail(e.getMessage());
            }
        }

        void advance() {
            try {
                UrbiParser.Command c = statement.command();
                if (c instanceof Block) {
                    advanceBlock();
                } else if (c instanceof Every e) {
                    advanceRepeat(e.body());
                } else if (c instanceof Loop l) {
                    advanceRepeat(l.body());
                } else if (motion != null && motion.ended()) {
                    finish();
                }
            } catch (UrbiError e) {
                fail(e.getMessage());
            }
        }

        private void advanceBlock() {
            List<Statement> list = ((Block) statement.command()).statements();
            while (true) {
                children.removeIf(c -> {
                    if (!c.done) {
                        c.advance();
                    }
                    return c.done;
                });
                if (waiting != null && !waiting.done) {
                    return;
                }
                waiting = null;
                if (next >= list.size()) {
                    if (children.isEmpty()) {
                        finish();
                    }
                    return;
                }
                Statement st = list.get(next++);
                if (!session.roomFor(st)) {
                    session.emit(st.tag().isEmpty() ? tag : st.tag(), Kind.ERROR, TOO_MANY_JOBS);
                    continue;
                }
                Job child = start(session, st, tag);
                if (!child.done) {
                    children.add(child);
                    if (st.sequential()) {
                        waiting = child;
                    }
                }
            }
        }

        private void advanceRepeat(Statement body) {
            children.removeIf(c -> {
                if (!c.done) {
                    c.advance();
                }
                return c.done;
            });
            long now = nanos.getAsLong();
            if (now >= nextAt && session.roomFor(body)) {
                nextAt = period <= 0 ? now + 1 : Math.max(nextAt + Math.round(period * 1e9), now);
                Job child = start(session, body, tag);
                if (!child.done) {
                    children.add(child);
                }
            }
        }

        private void keyword(String word) {
            switch (word) {
                case "motoron" -> motorsOn = true;
                case "motoroff" -> {
                    motorsOn = false;
                    dog.stop();
                }
                case "ping" -> session.emit(tag, Kind.SYSTEM, String.format(Locale.ROOT, "pong time=%.3fs", millis() / 1000.0));
                default -> throw new UrbiError("unknown command: " + word);
            }
        }

        private void assign(Assign a) {
            String target = a.target();
            if (target.equals("robot.watchdogInterval")) {
                double v = number(a.value());
                if (!(v >= 0) || v > 3600) {
                    throw new UrbiError("robot.watchdogInterval must be seconds in [0, 3600], got " + UrbiParser.format(v));
                }
                dog.watchdogInterval(v);
                finish();
                return;
            }
            if (target.endsWith(".val")) {
                String device = target.substring(0, target.length() - 4);
                Quadruped.Joint joint = dog.joint(device);
                if (joint == null) {
                    if (sensors.read(device).isPresent() || AiboDevices.SENSORS.contains(device)) {
                        throw new UrbiError(target + " is a sensor; it cannot be assigned");
                    }
                    throw new UrbiError("unknown identifier: " + target);
                }
                requireMotors(target);
                double degrees = number(a.value());
                double seconds = 0;
                for (var m : a.modifiers().entrySet()) {
                    switch (m.getKey()) {
                        case "time" -> seconds = m.getValue() instanceof Num n ? n.seconds() : number(m.getValue()) / 1000;
                        case "speed" -> {
                            double speed = number(m.getValue());
                            if (!(speed > 0)) {
                                throw new UrbiError("speed: must be > 0 degrees per second, got " + UrbiParser.format(speed));
                            }
                            seconds = Math.abs(joint.spec().clamp(degrees) - joint.angle()) / speed;
                        }
                        default -> throw new UrbiError("unknown modifier " + m.getKey() + ": (time: and speed: are known)");
                    }
                }
                if (!(seconds >= 0) || seconds > 3600) {
                    throw new UrbiError("time: must be in [0, 3600] seconds, got " + UrbiParser.format(seconds));
                }
                motion = dog.moveJoint(device, degrees, seconds);
                if (motion.ended()) {
                    finish();
                }
                return;
            }
            if (target.startsWith("robot.")) {
                throw new UrbiError(target + " cannot be assigned; robot.watchdogInterval can");
            }
            throw new UrbiError("unknown identifier: " + target);
        }

        private void evaluate(Expr e) {
            if (e instanceof Call c && c.name().startsWith("robot.")) {
                call(c);
                return;
            }
            if (e instanceof Str s) {
                session.emit(tag, Kind.VALUE, "\"" + s.value().replace("\\", "\\\\").replace("\"", "\\\"") + "\"");
            } else {
                session.emit(tag, Kind.VALUE, UrbiParser.format(number(e)));
            }
            finish();
        }

        private void call(Call c) {
            List<Expr> args = c.args();
            double maxSpeed = dog.drive().maxSpeed();
            double maxTurn = dog.drive().maxTurnRate();
            switch (c.name()) {
                case "robot.walk" -> {
                    arity(c, 2);
                    requireMotors(c.name());
                    double d = number(args.get(0));
                    double v = positive(c.name(), "speed", number(args.get(1)), maxSpeed, "m/s");
                    motion = dog.walk(d, v);
                }
                case "robot.turn" -> {
                    arity(c, 2);
                    requireMotors(c.name());
                    double a = number(args.get(0));
                    double w = positive(c.name(), "turn rate", number(args.get(1)), maxTurn, "rad/s");
                    motion = dog.turn(a, w);
                }
                case "robot.arc" -> {
                    arity(c, 3);
                    requireMotors(c.name());
                    double r = number(args.get(0));
                    double a = number(args.get(1));
                    double v = positive(c.name(), "speed", number(args.get(2)), maxSpeed, "m/s");
                    if (r == 0) {
                        throw new UrbiError("robot.arc: the radius must not be 0 (robot.turn turns on the spot)");
                    }
                    positive(c.name(), "turn rate speed/|radius|", v / Math.abs(r), maxTurn, "rad/s");
                    motion = dog.arc(r, a, v);
                }
                case "robot.drive" -> {
                    arity(c, 2);
                    requireMotors(c.name());
                    double v = number(args.get(0));
                    double w = number(args.get(1));
                    within(c.name(), "speed", v, maxSpeed, "m/s");
                    within(c.name(), "turn rate", w, maxTurn, "rad/s");
                    motion = dog.drive(v, w);
                }
                case "robot.stop" -> {
                    arity(c, 0);
                    dog.stop();
                }
                case "robot.sit" -> posture(c, Quadruped.Posture.SIT, SIT_SECONDS);
                case "robot.stand" -> posture(c, Quadruped.Posture.STAND, STAND_SECONDS);
                case "robot.lie" -> posture(c, Quadruped.Posture.LIE, LIE_SECONDS);
                case "robot.kick" -> {
                    arity(c, 0);
                    requireMotors(c.name());
                    motion = dog.kick(KICK_SECONDS);
                }
                default -> throw new UrbiError("unknown function: " + c.name());
            }
            if (motion == null || motion.ended()) {
                finish();
            }
        }

        private void posture(Call c, Quadruped.Posture p, double seconds) {
            arity(c, 0);
            requireMotors(c.name());
            motion = dog.posture(p, seconds);
        }

        private void requireMotors(String what) {
            if (!motorsOn) {
                throw new UrbiError(what + ": the motors are off (send motoron)");
            }
        }

        private void arity(Call c, int n) {
            if (c.args().size() != n) {
                throw new UrbiError(c.name() + " expects " + n + " argument" + (n == 1 ? "" : "s") + ", got " + c.args().size());
            }
        }

        private double positive(String fn, String what, double v, double max, String unit) {
            if (!(v > 0)) {
                throw new UrbiError(fn + ": the " + what + " must be > 0, got " + UrbiParser.format(v));
            }
            return within(fn, what, v, max, unit);
        }

        private double within(String fn, String what, double v, double max, String unit) {
            if (Math.abs(v) > max * (1 + 1e-9)) {
                throw new UrbiError(String.format(Locale.ROOT, "%s: the %s %.3f %s is above the gait's %.3f %s", fn, what, v, unit, max, unit));
            }
            return v;
        }

        private double number(Expr e) {
            if (e instanceof Num n) {
                return n.value();
            }
            if (e instanceof Neg n) {
                return -number(n.operand());
            }
            if (e instanceof Binary b) {
                double l = number(b.left());
                double r = number(b.right());
                if (b.op() == '/' && r == 0) {
                    throw new UrbiError("division by zero");
                }
                double v = switch (b.op()) {
                    case '+' -> l + r;
                    case '-' -> l - r;
                    case '*' -> l * r;
                    default -> l / r;
                };
                if (!Double.isFinite(v)) {
                    throw new UrbiError("the result is not a finite number");
                }
                return v;
            }
            if (e instanceof Ref r) {
                return read(r.name());
            }
            if (e instanceof Str s) {
                throw new UrbiError("\"" + s.value() + "\" is a string, not a number");
            }
            Call c = (Call) e;
            throw new UrbiError(c.name().startsWith("robot.") ? c.name() + " is a command, not a value" : "unknown function: " + c.name());
        }

        private double read(String name) {
            switch (name) {
                case "robot.watchdogInterval" -> {
                    return dog.watchdogInterval();
                }
                case "robot.maxSpeed" -> {
                    return dog.drive().maxSpeed();
                }
                case "robot.maxTurnRate" -> {
                    return dog.drive().maxTurnRate();
                }
                default -> {
                }
            }
            if (name.endsWith(".val")) {
                String device = name.substring(0, name.length() - 4);
                Quadruped.Joint j = dog.joint(device);
                if (j != null) {
                    return j.angle();
                }
                OptionalDouble v = sensors.read(device);
                if (v.isPresent()) {
                    return v.getAsDouble();
                }
            }
            throw new UrbiError("unknown identifier: " + name);
        }

        private void fail(String message) {
            session.emit(tag, Kind.ERROR, message);
            finish();
        }

        private void finish() {
            if (done) {
                return;
            }
            done = true;
            session.jobs--;
            if (statement.flags().contains("end")) {
                session.emit(tag, Kind.SYSTEM, "end");
            }
        }

        /** Stops this job and its children; a motion it drives stops where it is. */
        void stop() {
            for (Job c : List.copyOf(children)) {
                c.stop();
            }
            children.clear();
            if (motion != null && !motion.ended()) {
                if (dog.current() == motion) {
                    dog.stop();
                } else {
                    Quadruped.Joint j = dog.joint(motion.name());
                    if (j != null) {
                        dog.moveJoint(motion.name(), j.angle(), 0);
                    }
                }
            }
            finish();
        }

        void stopTagged(String t) {
            if (!statement.tag().isEmpty() && statement.tag().equals(t)) {
                stop();
                return;
            }
            for (Job c : List.copyOf(children)) {
                c.stopTagged(t);
            }
            children.removeIf(c -> c.done);
        }
    }

    /** A statement that failed: its message is the {@code !!!} text. */
    private static final class UrbiError extends RuntimeException {
        private static final long serialVersionUID = 1L;

        UrbiError(String message) {
            super(message, null, false, false);
        }
    }
}
