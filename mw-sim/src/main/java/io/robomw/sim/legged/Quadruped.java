package io.robomw.sim.legged;

import io.robomw.config.description.LeggedDrive;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.SplittableRandom;
import java.util.function.Consumer;

/**
 * A simulated four-legged robot's gait and joints, after the Sony Aibo ERS-7: what the walking
 * commands of its firmware do to the body and to the joints. The simulated robot sets its body's
 * velocities from {@link #linearVelocity()} and {@link #angularVelocity()} before each physics step
 * (dyn4j then resolves collisions, so a dog that walks into a wall stops at it) and calls
 * {@link #advance} after it.
 *
 * <h2>Gait model</h2>
 * <ul>
 *   <li>A body motion ({@link #walk}, {@link #turn}, {@link #arc}, {@link #drive}, a posture,
 *   a kick) runs for its commanded time, as the firmware counts its steps; a newer one ends the
 *   one before (it ends interrupted).</li>
 *   <li>Speed and turn rate are at most the drive's {@code max_speed} and {@code max_turn_rate}
 *   (the caller checks; a faster command is refused before it gets here).</li>
 *   <li>Each step of the gait ({@code 1 / step_frequency} seconds) the body goes a little faster
 *   or slower than commanded: factors {@code 1 + jitter·N(0, 1)} on speed and turn rate, drawn
 *   from a generator seeded by the world's seed, so runs repeat exactly. The feet slip: the
 *   motion is {@code (1 − slip)} of the commanded one.</li>
 *   <li>A continuous {@link #drive} ends by itself when it is not repeated within
 *   {@link #watchdogInterval()} seconds (0: never), as the Gostai Mobile interface's watchdog
 *   does.</li>
 * </ul>
 *
 * <h2>Joints</h2>
 * Every joint of the ERS-7 has an angle in degrees within its range. While the dog walks, its legs
 * swing in a trot (diagonal pairs together) at the step frequency; a posture moves them to its
 * pose; the head, tail and mouth follow the trajectories they are given ({@link #moveJoint}).
 *
 * <p>Not thread-safe: the simulation thread (or the world's worker for this robot) touches it.
 */
public final class Quadruped {

    /** Standard gravity, m/s². */
    public static final double GRAVITY = 9.81;
    /** How much the trunk bounces while walking, m/s² peak. */
    static final double BOUNCE = 1.2;
    /** How far each leg's shoulder or hip swings while walking, degrees either way. */
    static final double SWING_DEGREES = 22;
    /** How far each knee bends to lift its foot while walking, degrees. */
    static final double LIFT_DEGREES = 25;

    /** The robot's postures. */
    public enum Posture {
        /** On four legs. */
        STAND(0),
        /** On its hind legs, trunk pitched up. */
        SIT(Math.toRadians(35)),
        /** Lying down. */
        LIE(0);

        private final double pitch;

        Posture(double pitch) {
            this.pitch = pitch;
        }

        /** @return how far the trunk is pitched nose-up, radians */
        public double pitch() {
            return pitch;
        }
    }

    private final LeggedDrive drive;
    private final SplittableRandom random;
    private final Map<String, Joint> joints = new LinkedHashMap<>();
    private final List<Joint> legJoints = new ArrayList<>();
    private Motion current;
    private Posture posture = Posture.STAND;
    private double gaitPhase;
    private double stepTimer;
    private double speedFactor = 1;
    private double turnFactor = 1;
    private double watchdogInterval;
    private double time;

    /**
     * @param drive the legged drive (limits and gait)
     * @param seed  the seed of the jitter
     */
    public Quadruped(LeggedDrive drive, long seed) {
        this.drive = drive;
        this.random = new SplittableRandom(seed);
        for (AiboJoints.Spec spec : AiboJoints.ALL) {
            Joint j = new Joint(spec);
            joints.put(spec.device(), j);
            if (spec.leg()) {
                legJoints.add(j);
            }
        }
        setPose(Posture.STAND);
        drawFactors();
    }

    /** @return the legged drive */
    public LeggedDrive drive() {
        return drive;
    }

    // ---- body motions ----

    /**
     * Walks straight.
     *
     * @param distance metres, negative backwards
     * @param speed    metres per second, &gt; 0
     * @return the motion
     */
    public Motion walk(double distance, double speed) {
        return begin("walk", Math.signum(distance) * speed, 0, Math.abs(distance) / speed, Posture.STAND);
    }

    /**
     * Turns on the spot.
     *
     * @param angle radians, positive left
     * @param rate  radians per second, &gt; 0
     * @return the motion
     */
    public Motion turn(double angle, double rate) {
        return begin("turn", 0, Math.signum(angle) * rate, Math.abs(angle) / rate, Posture.STAND);
    }

    /**
     * Walks an arc.
     *
     * @param radius metres, positive centre on the left, not 0
     * @param angle  radians of arc, positive forwards
     * @param speed  metres per second, &gt; 0
     * @return the motion
     */
    public Motion arc(double radius, double angle, double speed) {
        double v = Math.signum(angle) * speed;
        return begin("arc", v, v / radius, Math.abs(radius * angle) / speed, Posture.STAND);
    }

    /**
     * Walks on at velocities until replaced, stopped, or not repeated within the watchdog interval.
     *
     * @param linear  metres per second
     * @param angular radians per second
     * @return the motion
     */
    public Motion drive(double linear, double angular) {
        return begin("drive", linear, angular, Double.POSITIVE_INFINITY, Posture.STAND);
    }

    /**
     * Takes a posture (the legs move to it over the time given); the body stands still.
     *
     * @param p       the posture
     * @param seconds how long it takes
     * @return the motion
     */
    public Motion posture(Posture p, double seconds) {
        return begin(p.name().toLowerCase(java.util.Locale.ROOT), 0, 0, seconds, p);
    }

    /**
     * Kicks with a front leg, standing.
     *
     * @param seconds how long it takes
     * @return the motion
     */
    public Motion kick(double seconds) {
        return begin("kick", 0, 0, seconds, Posture.STAND);
    }

    /** Ends the current body motion (interrupted); the dog stands still where it is. */
    public void stop() {
        if (current != null) {
            Motion m = current;
            current = null;
            m.end(false);
        }
    }

    /** @return the current body motion, or {@code null} */
    public Motion current() {
        return current;
    }

    /** @return seconds a {@link #drive} lasts without being repeated; 0 never ends it */
    public double watchdogInterval() {
        return watchdogInterval;
    }

    /**
     * @param seconds seconds a {@link #drive} lasts without being repeated, ≥ 0; 0 never ends it
     */
    public void watchdogInterval(double seconds) {
        if (!(seconds >= 0) || !Double.isFinite(seconds)) {
            throw new IllegalArgumentException("watchdogInterval must be a number >= 0 seconds, got " + seconds);
        }
        this.watchdogInterval = seconds;
    }

    private Motion begin(String name, double linear, double angular, double seconds, Posture target) {
        stop();
        Motion m = new Motion(name, linear, angular, seconds, target);
        current = m;
        if (target != posture) {
            m.from = posture;
        }
        return m;
    }

    // ---- joints ----

    /**
     * @param device a joint's URBI name ({@code headPan}, {@code legLF1})
     * @return the joint, or {@code null} if the dog has none of that name
     */
    public Joint joint(String device) {
        return joints.get(device);
    }

    /** @return every joint, by URBI name */
    public Map<String, Joint> joints() {
        return java.util.Collections.unmodifiableMap(joints);
    }

    /**
     * Moves a joint to an angle over a time (at once for 0), ending the trajectory it followed.
     *
     * @param device  the joint
     * @param degrees the target, clamped to the joint's range
     * @param seconds how long, ≥ 0
     * @return the trajectory, as a motion that ends when the joint is there
     * @throws IllegalArgumentException if the dog has no such joint
     */
    public Motion moveJoint(String device, double degrees, double seconds) {
        Joint j = joints.get(device);
        if (j == null) {
            throw new IllegalArgumentException("no joint " + device);
        }
        if (j.trajectory != null) {
            Motion old = j.trajectory;
            j.trajectory = null;
            old.end(false);
        }
        Motion m = new Motion(device, 0, 0, Math.max(0, seconds), null);
        j.start = j.angle;
        j.target = j.spec.clamp(degrees);
        j.trajectory = m;
        if (seconds <= 0) {
            j.angle = j.target;
            j.trajectory = null;
            m.end(true);
        }
        return m;
    }

    // ---- stepping ----

    /** @return the body's forward velocity for the next step, m/s (jitter and slip included) */
    public double linearVelocity() {
        return current == null ? 0 : current.linear * speedFactor * (1 - drive.gait().slip());
    }

    /** @return the body's turn rate for the next step, rad/s (jitter and slip included) */
    public double angularVelocity() {
        return current == null ? 0 : current.angular * turnFactor * (1 - drive.gait().slip());
    }

    /** @return whether the legs are walking (the body is commanded to move) */
    public boolean walking() {
        return current != null && (current.linear != 0 || current.angular != 0);
    }

    /** @return the posture */
    public Posture posture() {
        return posture;
    }

    /** @return the phase of the gait, radians (advances only while walking) */
    public double gaitPhase() {
        return gaitPhase;
    }

    /** @return the trunk's nose-up pitch now, radians */
    public double pitch() {
        Motion m = current;
        if (m != null && m.from != null && m.target != null && Double.isFinite(m.seconds) && m.seconds > 0) {
            double f = Math.min(1, m.elapsed / m.seconds);
            return m.from.pitch() + (m.target.pitch() - m.from.pitch()) * f;
        }
        return posture.pitch();
    }

    /** @return the trunk's vertical bounce from the gait now, m/s² */
    public double bounce() {
        return walking() ? BOUNCE * Math.sin(2 * gaitPhase) : 0;
    }

    /**
     * Advances the gait and the joints by one physics step, after the body has moved.
     *
     * @param dt the step, seconds
     */
    public void advance(double dt) {
        time += dt;
        Motion m = current;
        if (m != null) {
            m.elapsed += dt;
            if (walking()) {
                gaitPhase += 2 * Math.PI * drive.gait().stepFrequency() * dt;
                stepTimer += dt;
                if (stepTimer >= 1 / drive.gait().stepFrequency()) {
                    stepTimer = 0;
                    drawFactors();
                }
            }
            if (m.target != null && m.from != null) {
                blendPose(m.from, m.target, Math.min(1, m.elapsed / m.seconds));
            }
            boolean watchdog = Double.isInfinite(m.seconds) && watchdogInterval > 0 && m.elapsed > watchdogInterval;
            if (watchdog || m.elapsed >= m.seconds - 1e-9) {
                current = null;
                if (m.target != null) {
                    posture = m.target;
                    setPose(posture);
                }
                m.end(!watchdog);
            }
        }
        if (walking()) {
            swingLegs();
        }
        for (Joint j : joints.values()) {
            Motion t = j.trajectory;
            if (t != null) {
                t.elapsed += dt;
                double f = t.seconds <= 0 ? 1 : Math.min(1, t.elapsed / t.seconds);
                j.angle = j.start + (j.target - j.start) * f;
                if (f >= 1) {
                    j.trajectory = null;
                    t.end(true);
                }
            }
        }
    }

    private void drawFactors() {
        double jitter = drive.gait().jitter();
        speedFactor = jitter == 0 ? 1 : Math.max(0, 1 + jitter * gaussian());
        turnFactor = jitter == 0 ? 1 : Math.max(0, 1 + jitter * gaussian());
    }

    private double gaussian() {
        double u1 = 1.0 - random.nextDouble();
        double u2 = random.nextDouble();
        return Math.sqrt(-2 * Math.log(u1)) * Math.cos(2 * Math.PI * u2);
    }

    private void setPose(Posture p) {
        for (Joint j : legJoints) {
            j.angle = j.spec.clamp(AiboJoints.pose(p, j.spec));
        }
    }

    private void blendPose(Posture from, Posture to, double f) {
        for (Joint j : legJoints) {
            double a = AiboJoints.pose(from, j.spec);
            double b = AiboJoints.pose(to, j.spec);
            j.angle = j.spec.clamp(a + (b - a) * f);
        }
    }

    /** A trot: the diagonal pairs LF+RH and RF+LH swing in opposite phase. */
    private void swingLegs() {
        for (Joint j : legJoints) {
            double phase = gaitPhase + (j.spec.diagonal() ? 0 : Math.PI);
            double base = AiboJoints.pose(Posture.STAND, j.spec);
            double a = switch (j.spec.segment()) {
                case 1 -> base + SWING_DEGREES * Math.sin(phase);
                case 3 -> base + LIFT_DEGREES * Math.max(0, Math.sin(phase));
                default -> base;
            };
            j.angle = j.spec.clamp(a);
        }
    }

    /** One joint: its angle, and the trajectory it follows, if any. */
    public static final class Joint {
        private final AiboJoints.Spec spec;
        private double angle;
        private double start;
        private double target;
        private Motion trajectory;

        private Joint(AiboJoints.Spec spec) {
            this.spec = spec;
        }

        /** @return what the joint is */
        public AiboJoints.Spec spec() {
            return spec;
        }

        /** @return its angle, degrees */
        public double angle() {
            return angle;
        }
    }

    /**
     * A body motion or a joint's trajectory, from its start to its end. Its end listeners run once,
     * on the thread that steps the dog.
     */
    public static final class Motion {
        private final String name;
        private final double linear;
        private final double angular;
        private final double seconds;
        private final Posture target;
        private final List<Consumer<Boolean>> listeners = new ArrayList<>(2);
        private Posture from;
        private double elapsed;
        private boolean ended;
        private boolean completed;

        private Motion(String name, double linear, double angular, double seconds, Posture target) {
            this.name = name;
            this.linear = linear;
            this.angular = angular;
            this.seconds = seconds;
            this.target = target;
        }

        /** @return what it is ({@code walk}, {@code sit}, a joint's name) */
        public String name() {
            return name;
        }

        /** @return whether it has ended, completed or not */
        public boolean ended() {
            return ended;
        }

        /** @return whether it ran to its end (rather than being interrupted) */
        public boolean completed() {
            return completed;
        }

        /**
         * @param listener told once when it ends: {@code true} if it completed, {@code false} if
         *                 it was interrupted; at once if it already ended
         */
        public void onEnd(Consumer<Boolean> listener) {
            if (ended) {
                listener.accept(completed);
            } else {
                listeners.add(listener);
            }
        }

        private void end(boolean done) {
            if (ended) {
                return;
            }
            ended = true;
            completed = done;
            for (Consumer<Boolean> l : listeners) {
                l.accept(done);
            }
            listeners.clear();
        }

        @Override
        public String toString() {
            return "Motion[" + name + (ended ? completed ? " completed" : " interrupted" : " running") + "]";
        }
    }
}
