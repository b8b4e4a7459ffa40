package io.robomw.sim;

import io.robomw.api.Position;
import io.robomw.api.SensorType;
import io.robomw.config.description.Body;
import io.robomw.config.description.SensorSpec;

import java.util.Map;
import java.util.SplittableRandom;

/**
 * How the simulator models one sensor of a robot: where it is mounted on the body and, for range
 * sensors, its beam. Defaults follow the sensor's type and position; the robot description's
 * sensor {@code options} override them:
 *
 * <table>
 *   <caption>options read by the simulator</caption>
 *   <tr><th>option</th><th>meaning</th><th>default</th></tr>
 *   <tr><td>{@code x}, {@code y}</td><td>mount point on the body, metres from its centre (x forwards, y left)</td><td>the edge the position names</td></tr>
 *   <tr><td>{@code angle}</td><td>direction the sensor faces, radians from forwards</td><td>the position's direction</td></tr>
 *   <tr><td>{@code beam_width}</td><td>full cone angle of a range sensor, radians</td><td>sonar 0.5, infra-red 0</td></tr>
 *   <tr><td>{@code rays}</td><td>rays cast across the cone; the nearest hit counts</td><td>sonar 5, infra-red 1</td></tr>
 *   <tr><td>{@code min_range}, {@code max_range}</td><td>metres; beyond max the sensor reports max</td><td>sonar 0.03–2.55, infra-red 0.06–0.80</td></tr>
 *   <tr><td>{@code noise}</td><td>standard deviation of Gaussian noise, metres (seeded)</td><td>0</td></tr>
 *   <tr><td>{@code rate_hz}</td><td>samples per simulated second</td><td>10</td></tr>
 *   <tr><td>{@code mount}</td><td>{@code head}: the sensor sits in a legged robot's head, so its
 *   ray turns with the head's pan, and sees the floor when the head looks down</td><td>{@code body}</td></tr>
 *   <tr><td>{@code height}</td><td>of a head-mounted sensor above the floor, metres</td><td>0.2</td></tr>
 *   <tr><td>{@code axis}</td><td>of an accelerometer: {@code x} forwards, {@code y} left, {@code z} up</td>
 *   <td>the port's last letter, if x, y or z; else x</td></tr>
 * </table>
 *
 * <p>One model serves every robot of a world read from the same robot file (its geometry is the
 * file's): immutable, any thread. What a robot's sensor reads is the robot's ({@link SimRobot#latest}),
 * kept in the world's arrays; a noisy sensor draws from the robot's own seeded generator.
 */
public final class SensorModel {

    /** What the simulator computes for a sensor. */
    public enum Kind {
        /** Ray casts against walls, obstacles and other robots. */
        RANGE,
        /** Contact on the side it faces. */
        CONTACT,
        /** Floor brightness or colour under it. */
        FLOOR,
        /** Absolute heading. */
        HEADING,
        /** Heading turned since the start. */
        TURNED,
        /** A quiet world: silence. */
        SILENCE,
        /** A motor's encoder (read through the motor platform). */
        TACHO,
        /** Acceleration of the body along one axis. */
        ACCELERATION,
        /** A legged robot's joint angle. */
        JOINT,
        /** What a vehicle's autopilot reports: its altitude, battery, latitude or longitude (0 on a robot that is no vehicle). */
        VEHICLE
    }

    private final SensorSpec spec;
    private final Kind kind;
    private final double mountX;
    private final double mountY;
    private final double mountAngle;
    private final double beamWidth;
    private final int rays;
    private final double minRange;
    private final double maxRange;
    private final double noise;
    private final double rateHz;
    private final boolean headMounted;
    private final double height;
    private final char axis;
    /** Its place among its robot file's range sensors, or -1 if it is not one. */
    private final int rangeIndex;
    /** Every how many steps of its world it samples. */
    private final long everySteps;
    /** Each ray's direction on the body (from forwards), its cosine and sine. */
    private final double[] rayCos;
    private final double[] raySin;

    /**
     * @param spec       the sensor as its robot file describes it
     * @param body       the robot's body (the default mount points lie on its edges)
     * @param rangeIndex its place among the file's range sensors, or -1
     * @param physicsHz  its world's step rate
     */
    SensorModel(SensorSpec spec, Body body, int rangeIndex, double physicsHz) {
        this.spec = spec;
        this.rangeIndex = rangeIndex;
        this.kind = kindOf(spec.type());
        Map<String, Object> o = spec.options();
        double[] mount = defaultMount(spec.position(), body);
        boolean sonar = spec.type() == SensorType.SONAR;
        this.mountX = number(o, "x", mount[0], -MAX_MOUNT, MAX_MOUNT);
        this.mountY = number(o, "y", mount[1], -MAX_MOUNT, MAX_MOUNT);
        this.mountAngle = number(o, "angle", mount[2], -2 * Math.PI, 2 * Math.PI);
        this.beamWidth = number(o, "beam_width", sonar ? 0.5 : 0, 0, 2 * Math.PI);
        this.rays = (int) integer(o, "rays", sonar ? 5 : 1, 1, MAX_RAYS);
        this.minRange = number(o, "min_range", sonar ? 0.03 : 0.06, 0, MAX_RANGE);
        this.maxRange = number(o, "max_range", sonar ? 2.55 : 0.80, 0, MAX_RANGE);
        this.noise = number(o, "noise", 0, 0, MAX_NOISE);
        this.rateHz = number(o, "rate_hz", 10, 0.001, MAX_RATE_HZ);
        this.everySteps = everySteps(physicsHz);
        Object mountOption = o.getOrDefault("mount", "body");
        if (!mountOption.equals("body") && !mountOption.equals("head")) {
            throw new IllegalArgumentException("sensor '" + spec.name() + "': option 'mount' must be body or head, got '" + mountOption + "'");
        }
        this.headMounted = mountOption.equals("head");
        this.height = number(o, "height", 0.2, 0, MAX_MOUNT);
        this.axis = axisOf(spec, o);
        this.rayCos = new double[rays];
        this.raySin = new double[rays];
        for (int i = 0; i < rays; i++) {
            double a = rays == 1 ? mountAngle : mountAngle - beamWidth / 2 + beamWidth * i / (rays - 1);
            rayCos[i] = Math.cos(a);
            raySin[i] = Math.sin(a);
        }
        if (!(maxRange > minRange)) {
            throw new IllegalArgumentException("sensor '" + spec.name() + "': option 'max_range' (" + maxRange + ") must be above 'min_range' ("
                    + minRange + ")");
        }
    }

    /** Farthest mount point from the body's centre, metres (a body is at most 100 m long). */
    static final double MAX_MOUNT = 100;
    /** Most rays across one sensor's cone. */
    static final int MAX_RAYS = 100;
    /** Longest range, metres. */
    static final double MAX_RANGE = 1000;
    /** Largest noise standard deviation, metres. */
    static final double MAX_NOISE = 100;
    /** Fastest sampling, per simulated second. */
    static final double MAX_RATE_HZ = 1000;

    private double number(Map<String, Object> options, String key, double fallback, double min, double max) {
        Object v = options.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Number n && n.doubleValue() >= min && n.doubleValue() <= max) {
            return n.doubleValue();
        }
        throw new IllegalArgumentException("sensor '" + spec.name() + "': option '" + key + "' must be a number from " + min + " to " + max
                + ", got '" + v + "' (the simulator's sensor options are in docs/simulation.md)");
    }

    private long integer(Map<String, Object> options, String key, long fallback, long min, long max) {
        Object v = options.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Number n && n.doubleValue() == Math.rint(n.doubleValue()) && n.doubleValue() >= min && n.doubleValue() <= max) {
            return n.longValue();
        }
        throw new IllegalArgumentException("sensor '" + spec.name() + "': option '" + key + "' must be a whole number from " + min + " to " + max
                + ", got '" + v + "' (the simulator's sensor options are in docs/simulation.md)");
    }

    static Kind kindOf(SensorType type) {
        return switch (type) {
            case SONAR, INFRARED, LASER, RANGE -> Kind.RANGE;
            case ALTITUDE, BATTERY, LATITUDE, LONGITUDE -> Kind.VEHICLE;
            case TOUCH -> Kind.CONTACT;
            case LIGHT, COLOR -> Kind.FLOOR;
            case COMPASS -> Kind.HEADING;
            case GYRO -> Kind.TURNED;
            case SOUND -> Kind.SILENCE;
            case TACHO -> Kind.TACHO;
            case ACCELEROMETER -> Kind.ACCELERATION;
            case JOINT -> Kind.JOINT;
        };
    }

    private static char axisOf(SensorSpec spec, Map<String, Object> o) {
        Object given = o.get("axis");
        String a = given != null ? given.toString() : spec.port().isEmpty() ? "x" : spec.port().substring(spec.port().length() - 1);
        a = a.toLowerCase(java.util.Locale.ROOT);
        if (a.equals("x") || a.equals("y") || a.equals("z")) {
            return a.charAt(0);
        }
        if (given != null) {
            throw new IllegalArgumentException(spec.name() + ": sensor option axis must be x, y or z, got '" + given + "'");
        }
        return 'x';
    }

    /** {x, y, angle} of the middle of the body edge the position names. */
    private static double[] defaultMount(Position p, Body b) {
        double hl = b.length() / 2;
        double hw = b.width() / 2;
        return switch (p) {
            case FRONT -> new double[]{hl, 0, 0};
            case BACK -> new double[]{-hl, 0, Math.PI};
            case LEFT -> new double[]{0, hw, Math.PI / 2};
            case RIGHT -> new double[]{0, -hw, -Math.PI / 2};
            case FRONT_LEFT -> new double[]{hl, hw, Math.PI / 4};
            case FRONT_RIGHT -> new double[]{hl, -hw, -Math.PI / 4};
            case BACK_LEFT -> new double[]{-hl, hw, 3 * Math.PI / 4};
            case BACK_RIGHT -> new double[]{-hl, -hw, -3 * Math.PI / 4};
            case TOP, BOTTOM, CENTER -> new double[]{0, 0, 0};
        };
    }

    /** @return the sensor's description */
    public SensorSpec spec() {
        return spec;
    }

    /** @return what the simulator computes for it */
    public Kind kind() {
        return kind;
    }

    /** @return mount point x on the body, metres forwards of its centre */
    public double mountX() {
        return mountX;
    }

    /** @return mount point y on the body, metres left of its centre */
    public double mountY() {
        return mountY;
    }

    /** @return the direction it faces, radians from the body's forwards */
    public double mountAngle() {
        return mountAngle;
    }

    /** @return its place among its robot's range sensors ({@link SimRobot#rangeSensors()}), or -1 if it is not a range sensor */
    public int rangeIndex() {
        return rangeIndex;
    }

    /** @return whether its readings are noisy (each robot's then draws from a seeded generator of its own) */
    public boolean noisy() {
        return noise > 0;
    }

    /** @return the full cone angle of a range sensor, radians */
    public double beamWidth() {
        return beamWidth;
    }

    /** @return rays cast across the cone */
    public int rays() {
        return rays;
    }

    /** @return the shortest distance it reports */
    public double minRange() {
        return minRange;
    }

    /** @return the longest distance it reports */
    public double maxRange() {
        return maxRange;
    }

    /** @return whether it sits in a legged robot's head and turns with it */
    public boolean headMounted() {
        return headMounted;
    }

    /** @return how far from the robot's centre a point of its rays can be: its mount's distance plus its longest range */
    double reach() {
        return Math.sqrt(mountX * mountX + mountY * mountY) + maxRange;
    }

    /**
     * Stretches a box, in the robot's frame, over its rays (their origins and their ends at the longest range).
     *
     * @param box {minX, minY, maxX, maxY}
     * @return false, leaving the box, if the rays turn with a head (no box in the robot's frame holds them)
     */
    boolean stretch(double[] box) {
        if (headMounted) {
            return false;
        }
        for (int i = 0; i < rays; i++) {
            double ex = mountX + maxRange * rayCos[i];
            double ey = mountY + maxRange * raySin[i];
            box[0] = Math.min(box[0], Math.min(mountX, ex));
            box[1] = Math.min(box[1], Math.min(mountY, ey));
            box[2] = Math.max(box[2], Math.max(mountX, ex));
            box[3] = Math.max(box[3], Math.max(mountY, ey));
        }
        return true;
    }

    /** @return an accelerometer's axis: {@code x} forwards, {@code y} left, {@code z} up */
    public char axis() {
        return axis;
    }

    /** @return samples per simulated second */
    public double rateHz() {
        return rateHz;
    }

    /**
     * @param physicsHz the world's step rate
     * @return every how many steps it samples
     */
    long everySteps(double physicsHz) {
        return Math.max(1, Math.round(physicsHz / rateHz));
    }

    /** @return every how many steps of its world it samples */
    long everySteps() {
        return everySteps;
    }

    /**
     * Samples a range sensor ray by ray (the naive baseline's dyn4j ray casts), the heading's
     * cosine and sine given.
     *
     * @param caster  casts one ray
     * @param self    the robot's index
     * @param x       robot centre x
     * @param y       robot centre y
     * @param heading robot heading
     * @param c       {@code Math.cos(heading)}
     * @param s       {@code Math.sin(heading)}
     * @param pan     the head's pan, radians
     * @param tilt    the head's tilt, radians
     * @param random  the robot's generator for this sensor's noise, or {@code null} if it has none
     * @return the sample, metres
     */
    double sampleRange(SimWorld.RayCaster caster, int self, double x, double y, double heading, double c, double s, double pan, double tilt,
                       SplittableRandom random) {
        double ox = x + mountX * c - mountY * s;
        double oy = y + mountX * s + mountY * c;
        double centre = heading + mountAngle + (headMounted ? pan : 0);
        double best = Double.POSITIVE_INFINITY;
        for (int i = 0; i < rays; i++) {
            double a = rays == 1 ? centre : centre - beamWidth / 2 + beamWidth * i / (rays - 1);
            best = Math.min(best, caster.cast(ox, oy, a, maxRange, self));
        }
        return finish(best, tilt, random);
    }

    /**
     * Adds the rays of a range sensor to a robot's batch (their origins, directions and range), for
     * {@link #finishRange} once they are cast.
     *
     * @param batch   the robot's rays so far
     * @param x       robot centre x
     * @param y       robot centre y
     * @param heading robot heading
     * @param c       {@code Math.cos(heading)}
     * @param s       {@code Math.sin(heading)}
     * @param pan     the head's pan, radians
     */
    void addRays(RayBatch batch, double x, double y, double heading, double c, double s, double pan) {
        double ox = x + mountX * c - mountY * s;
        double oy = y + mountX * s + mountY * c;
        if (headMounted) {
            double centre = heading + mountAngle + pan;
            for (int i = 0; i < rays; i++) {
                double a = rays == 1 ? centre : centre - beamWidth / 2 + beamWidth * i / (rays - 1);
                batch.add(ox, oy, Math.cos(a), Math.sin(a), maxRange);
            }
            return;
        }
        // each ray's direction on the body, turned by the heading: no sine or cosine per ray
        for (int i = 0; i < rays; i++) {
            double u = rayCos[i];
            double v = raySin[i];
            batch.add(ox, oy, c * u - s * v, s * u + c * v, maxRange);
        }
    }

    /**
     * Takes the sample from this sensor's rays once they are cast: as {@link #sampleRange} does.
     *
     * @param hits   the distances of the batch's rays (+∞: nothing within range)
     * @param first  the index of this sensor's first ray in the batch
     * @param tilt   the head's tilt, radians, positive up
     * @param random the robot's generator for this sensor's noise, or {@code null} if it has none
     * @return the sample, metres
     */
    double finishRange(double[] hits, int first, double tilt, SplittableRandom random) {
        double best = Double.POSITIVE_INFINITY;
        for (int i = 0; i < rays; i++) {
            best = Math.min(best, hits[first + i]);
        }
        return finish(best, tilt, random);
    }

    /** The nearest hit as the sensor reports it: the floor a head looking down sees, the range's limits, the noise. */
    private double finish(double best, double tilt, SplittableRandom random) {
        double floor = headMounted && tilt < -1e-3 ? height / Math.tan(-tilt) : Double.POSITIVE_INFINITY;
        best = Math.min(best, floor);
        double value = Double.isInfinite(best) || best > maxRange ? maxRange : best;
        if (noise > 0) {
            value += gaussian(random) * noise;
        }
        return Math.min(maxRange, Math.max(minRange, value));
    }

    /** A robot's rays of one sensing pass, cast together ({@link io.robomw.sim.sensing.RangeIndex#castRays}); one per thread (per {@link Parallel#slot}). */
    static final class RayBatch {
        double[] ox = new double[16];
        double[] oy = new double[16];
        double[] dx = new double[16];
        double[] dy = new double[16];
        double[] maxRange = new double[16];
        double[] hits = new double[16];
        int count;
        /** The range index's scratch for these rays' casts. */
        final io.robomw.sim.sensing.RangeIndex.Gathered gathered = new io.robomw.sim.sensing.RangeIndex.Gathered();
        /** Which of a robot file's range sensors are due at a step: the last list and step asked about, and the answer. */
        private java.util.List<SensorModel> dueSensors;
        private long dueStep;
        private boolean[] due = new boolean[0];

        /**
         * @param sensors a robot's range sensors (the list its robot file's robots share)
         * @param step    the step, or -1 for every sensor
         * @return whether each is due; the same answer for every robot of the file at that step, worked out once a step per
         *         thread rather than by a division per sensor and robot
         */
        boolean[] due(java.util.List<SensorModel> sensors, long step) {
            if (sensors != dueSensors || step != dueStep) {
                boolean[] d = due.length == sensors.size() ? due : new boolean[sensors.size()];
                for (int k = 0; k < d.length; k++) {
                    d[k] = step < 0 || step % sensors.get(k).everySteps() == 0;
                }
                due = d;
                dueSensors = sensors;
                dueStep = step;
            }
            return due;
        }

        void add(double x, double y, double ux, double uy, double range) {
            if (count == ox.length) {
                int m = 2 * count;
                ox = java.util.Arrays.copyOf(ox, m);
                oy = java.util.Arrays.copyOf(oy, m);
                dx = java.util.Arrays.copyOf(dx, m);
                dy = java.util.Arrays.copyOf(dy, m);
                maxRange = java.util.Arrays.copyOf(maxRange, m);
                hits = new double[m];
            }
            ox[count] = x;
            oy[count] = y;
            dx[count] = ux;
            dy[count] = uy;
            maxRange[count] = range;
            count++;
        }
    }

    private static double gaussian(SplittableRandom random) {
        // Box-Muller on the robot's own seeded generator for the sensor, so results do not depend on threads.
        double u1 = 1.0 - random.nextDouble();
        double u2 = random.nextDouble();
        return Math.sqrt(-2 * Math.log(u1)) * Math.cos(2 * Math.PI * u2);
    }
}
