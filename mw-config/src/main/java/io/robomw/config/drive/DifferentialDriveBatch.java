package io.robomw.config.drive;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.kinematics.DifferentialKinematics;

import java.util.List;

/**
 * The Configuration Layer of a batch of robots of one robot file on two driven wheels (a swarm),
 * over arrays: what {@link DifferentialDriveControl} does for one robot's {@code drive(v, ω)}, for
 * each member of a {@link WheelBatch} (the Platform Layer of the batch). The same conversion ({@link DifferentialKinematics}: body
 * velocities to signed wheel motor speeds, with the description's geometry and reversed motors),
 * the same checks (finite speeds, each wheel within {@code drive.max_speed}, refused with the
 * same {@link io.robomw.api.UnsupportedActionException} naming the robot), and the same odometry
 * (the wheels' travel integrated as an arc at each motion's start, as {@code WheelOdometry} does),
 * then the Platform Layer's motor command: the member's refreshed wheel speeds in the batch.
 *
 * <h2>Threads</h2>
 * A member is driven by one thread at a time (the world's worker that handles it), different
 * members on different threads at once: each touches only its own slots. {@link #pose} reads a
 * member's estimate on the same terms.
 */
public final class DifferentialDriveBatch {

    private final DifferentialKinematics kinematics;
    private final WheelBatch platform;
    private final List<String> names;
    private final double maxSpeed;
    private final double half;
    private final double degreesPerMetre;
    private final double leftSign;
    private final double rightSign;
    // the odometry of each member: its estimate and the last encoder readings integrated (NaN: none yet)
    private final double[] x;
    private final double[] y;
    private final double[] heading;
    private final double[] lastLeft;
    private final double[] lastRight;
    /**
     * Per member: the sine and cosine of its heading, and the heading they are of (NaN: none). The arc that last moved
     * a member computed them for the heading it ended at, and the next arc starts there: one sine and one cosine an
     * arc instead of two each (a swarm's members integrate at every tick), the same numbers as computing them anew.
     */
    private final double[] sinOf;
    private final double[] cosOf;
    private final double[] trigHeading;

    /**
     * @param description the robot file every member was loaded from (a ground robot on a differential drive)
     * @param platform    the members' Platform Layer, whose ports are the drive's left and right motors in that order
     * @param names       the members' names, by member index, for messages
     * @throws IllegalArgumentException if the description has no differential drive, is not a ground
     *                                  robot, or the batch's ports are not its drive's
     */
    public DifferentialDriveBatch(RobotDescription description, WheelBatch platform, List<String> names) {
        DifferentialDrive drive = description.drive().orElseThrow(() -> new IllegalArgumentException(
                "robot file of '" + description.name() + "' (" + description.source() + ") has no differential drive to batch"));
        if (!description.capabilities().contains(Capability.GROUND)) {
            throw new IllegalArgumentException("robot file of '" + description.name() + "' is a " + description.capabilities()
                    + " robot, not a GROUND one: it cannot drive in a batch");
        }
        if (!platform.ports().equals(List.of(drive.left().port(), drive.right().port()))) {
            throw new IllegalArgumentException("batch '" + platform.name() + "' drives ports " + platform.ports() + ", not the drive's "
                    + List.of(drive.left().port(), drive.right().port()));
        }
        if (names.size() != platform.members()) {
            throw new IllegalArgumentException("batch '" + platform.name() + "' has " + platform.members() + " members, got " + names.size() + " names");
        }
        this.kinematics = new DifferentialKinematics(drive);
        this.platform = platform;
        this.names = List.copyOf(names);
        this.maxSpeed = drive.maxSpeed();
        this.half = drive.trackWidth() / 2;
        this.degreesPerMetre = kinematics.motorDegreesPerMetre();
        this.leftSign = drive.left().reversed() ? -1 : 1;
        this.rightSign = drive.right().reversed() ? -1 : 1;
        int n = platform.members();
        this.x = new double[n];
        this.y = new double[n];
        this.heading = new double[n];
        this.lastLeft = new double[n];
        this.lastRight = new double[n];
        java.util.Arrays.fill(lastLeft, Double.NaN);
        java.util.Arrays.fill(lastRight, Double.NaN);
        this.sinOf = new double[n];
        this.cosOf = new double[n];
        this.trigHeading = new double[n];
        java.util.Arrays.fill(trigHeading, Double.NaN);
    }

    /** @return the members' Platform Layer */
    public WheelBatch platform() {
        return platform;
    }

    /**
     * Starts recording a member's odometry from its encoders now (the pose where it starts is the
     * origin, as a robot's own odometry starts when its drive is chosen).
     *
     * @param member the member
     */
    public void startOdometry(int member) {
        integrate(member);
    }

    /**
     * A member's {@code drive(v, ω)}: continuous velocities until the next drive, as
     * {@link DifferentialDriveControl#drive} for one robot; returns at once.
     *
     * @param member       the member
     * @param linearSpeed  metres per second, negative backwards
     * @param angularSpeed radians per second, positive left
     * @throws io.robomw.api.UnsupportedActionException naming the robot if a speed is not finite or a
     *                                                  wheel would exceed {@code drive.max_speed}
     */
    public void drive(int member, double linearSpeed, double angularSpeed) {
        if (!Double.isFinite(linearSpeed) || !Double.isFinite(angularSpeed)) {
            Call call = new Call(names.get(member), "drive");
            call.finite(linearSpeed, "linear speed");
            call.finite(angularSpeed, "angular speed");
        }
        // DifferentialKinematics.velocity, without its WheelMotion
        double left = (linearSpeed - angularSpeed * half) * degreesPerMetre;
        double right = (linearSpeed + angularSpeed * half) * degreesPerMetre;
        double fastest = Math.max(Math.abs(left), Math.abs(right)) / degreesPerMetre;
        if (fastest > maxSpeed) {
            new Call(names.get(member), "drive").atMost(fastest, maxSpeed, "wheel speed", "m/s", "drive.max_speed");
        }
        integrate(member);
        platform.refresh(member, leftSign * left, rightSign * right);
    }

    /**
     * @param member the member
     * @return its pose by odometry now (the encoders' travel since the last motion integrated)
     */
    public Pose pose(int member) {
        integrate(member);
        return new Pose(x[member], y[member], heading[member]);
    }

    /**
     * @param member the member
     * @param pose   its pose now; what follows integrates from its encoders now
     */
    public void resetPose(int member, Pose pose) {
        integrate(member);
        x[member] = pose.x();
        y[member] = pose.y();
        heading[member] = pose.heading();
        trigHeading[member] = Double.NaN;
    }

    /** Integrates a member's wheel travel since its last readings as one arc ({@link io.robomw.config.kinematics.Odometry}'s arithmetic). */
    private void integrate(int member) {
        double l = platform.degrees(member, 0);
        double r = platform.degrees(member, 1);
        double l0 = lastLeft[member];
        double r0 = lastRight[member];
        lastLeft[member] = l;
        lastRight[member] = r;
        if (!Double.isNaN(l0)) {
            advance(member, leftSign * (l - l0) / degreesPerMetre, rightSign * (r - r0) / degreesPerMetre);
        }
    }

    private void advance(int member, double left, double right) {
        double ds = (left + right) / 2;
        double dTheta = (right - left) / (2 * half);
        double h = heading[member];
        // the sine and cosine of h: the last arc's, when it ended at h (bit for bit: a heading is always finite, never NaN)
        boolean known = Double.doubleToRawLongBits(trigHeading[member]) == Double.doubleToRawLongBits(h);
        double sinH = known ? sinOf[member] : Math.sin(h);
        double cosH = known ? cosOf[member] : Math.cos(h);
        double nx;
        double ny;
        double nh = h + dTheta;
        double sinN;
        double cosN;
        if (Math.abs(dTheta) < 1e-12) {
            nx = x[member] + ds * cosH;
            ny = y[member] + ds * sinH;
            boolean same = Double.doubleToRawLongBits(nh) == Double.doubleToRawLongBits(h);
            sinN = same ? sinH : Double.NaN;
            cosN = same ? cosH : Double.NaN;
        } else {
            double rad = ds / dTheta;
            sinN = Math.sin(nh);
            cosN = Math.cos(nh);
            nx = x[member] + rad * (sinN - sinH);
            ny = y[member] - rad * (cosN - cosH);
        }
        if (!Double.isFinite(nx) || !Double.isFinite(ny) || !Double.isFinite(nh)) {
            throw new IllegalArgumentException("robot '" + names.get(member) + "': odometry is no longer finite (" + nx + ", " + ny + ", " + nh
                    + "): an encoder reading is not a number");
        }
        x[member] = nx;
        y[member] = ny;
        double normal = Pose.normalize(nh);
        heading[member] = normal;
        // known for the next arc only if the heading kept is the one they are of (not wrapped, not an unknown straight step)
        boolean keep = !Double.isNaN(sinN) && Double.doubleToRawLongBits(normal) == Double.doubleToRawLongBits(nh);
        trigHeading[member] = keep ? normal : Double.NaN;
        sinOf[member] = sinN;
        cosOf[member] = cosN;
    }
}
