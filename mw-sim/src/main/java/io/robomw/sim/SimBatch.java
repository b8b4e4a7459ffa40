package io.robomw.sim;

import io.robomw.api.Pose;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.drive.DifferentialDriveBatch;
import io.robomw.config.drive.WheelBatch;
import io.robomw.platform.motor.BatchMotorDriver;
import io.robomw.platform.motor.MotorBatch;

import java.util.List;

/**
 * A batch of a world's robots of one robot file, driven together through the three layers over
 * arrays (a swarm's controller drives them at every tick): its {@code drive(v, ω)} goes through the
 * Configuration Layer's {@link DifferentialDriveBatch} (kinematics, checks, odometry), then the
 * Platform Layer's {@link MotorBatch} (a drive command per member, refreshes, watchdog, the
 * member's cycle at its robot file's cycle rate), then this batch's motor driver, which sets the
 * simulated motors' speeds in the world's arrays and reads their encoders there: what each robot's
 * own {@code ConfiguredRobot}, execution action thread, motor platform and {@code SimMotorDriver}
 * do, without touching an object of the robot.
 *
 * <p>A member a program or an agent addresses one by one (any verb of its {@link io.robomw.api.Robot})
 * is <em>promoted</em> out of the batch by the world at the start of the next step
 * ({@link SimWorld#requestPromotion}): the batch releases it (its drive ends, its motors brake),
 * its own platform takes over from there, with the batch's odometry handed over as its pose.
 *
 * <p>Touched by the world's threads only: a member by the worker that handles its robot in a pass,
 * promotions by the stepping thread between passes.
 */
public final class SimBatch implements WheelBatch, BatchMotorDriver {

    private final String name;
    /** By member: the robot's index in the world. */
    private final int[] robots;
    private final RobotStates states;
    private final MotorBatch motors;
    private final DifferentialDriveBatch drive;
    /** The members' cycle period (their robot file's), nanoseconds. */
    final long periodNanos;
    /** When the members' next cycle is due, world clock nanoseconds; stepping thread. */
    long nextCycle;
    /** How many cycles are due in the step being taken (0 or more); written by the stepping thread before the pass. */
    int cyclesDue;

    /**
     * @param description the robot file of every member (a differential drive on a ground robot)
     * @param members     the members, in the world's order
     * @param states      the world's arrays
     * @param now         the world's clock now: the first cycle is due then
     */
    SimBatch(RobotDescription description, List<SimRobot> members, RobotStates states, long now) {
        DifferentialDrive d = description.drive().orElseThrow();
        this.name = java.util.Objects.requireNonNullElse(description.source(), description.name()); // its robot file names it in messages
        this.robots = members.stream().mapToInt(SimRobot::index).toArray();
        this.states = states;
        this.motors = new MotorBatch(name, List.of(d.left().port(), d.right().port()), robots.length, description.watchdogTimeout(), this);
        this.drive = new DifferentialDriveBatch(description, this, members.stream().map(SimRobot::name).toList());
        this.periodNanos = description.cyclePeriod().toNanos();
        this.nextCycle = now;
        for (int m = 0; m < robots.length; m++) {
            drive.startOdometry(m);
        }
    }

    // ---- the Configuration Layer's view of the batch's platform (WheelBatch) ----

    @Override
    public String name() {
        return name;
    }

    @Override
    public List<String> ports() {
        return motors.ports();
    }

    @Override
    public int members() {
        return robots.length;
    }

    @Override
    public void refresh(int member, double left, double right) {
        motors.refresh(member, left, right);
    }

    @Override
    public double degrees(int member, int motor) {
        int i = robots[member];
        return motor == 0 ? states.encoderLeft[i] : states.encoderRight[i];
    }

    // ---- the Platform Layer's driver (BatchMotorDriver) ----

    @Override
    public void send(int member, double[] speeds, int from) {
        int i = robots[member];
        states.command(i, speeds[from], speeds[from + 1]);
    }

    // ---- the world's side ----

    /**
     * A member's {@code drive(v, ω)} (the Instruction Layer's verb, for a controller that drives the
     * batch): through the Configuration Layer to the member's drive command.
     *
     * @param member       the member
     * @param linearSpeed  metres per second
     * @param angularSpeed radians per second, positive left
     * @throws io.robomw.api.UnsupportedActionException naming the robot, as {@code Robot.drive} would
     */
    void drive(int member, double linearSpeed, double angularSpeed) {
        drive.drive(member, linearSpeed, angularSpeed);
    }

    /** The member's cycles due in this step ({@link #cyclesDue}), at the world's time {@code now}. */
    void cycle(int member, long now) {
        for (int k = cyclesDue; k > 0; k--) {
            motors.cycle(member, now);
        }
    }

    /** What the member's part of a step threw (reported by the world): its drive ends, its motors brake. */
    void failed(int member) {
        motors.fail(member);
    }

    /**
     * Releases a member to its own platform; stepping thread, between passes.
     *
     * @return its pose by the batch's odometry, for its own odometry to go on from
     */
    Pose release(int member) {
        Pose pose = drive.pose(member);
        motors.release(member);
        return pose;
    }

    /** @return the robot's index in the world of a member */
    int robot(int member) {
        return robots[member];
    }

    /** @return the Platform Layer of the batch (for tests and diagnosis) */
    MotorBatch motors() {
        return motors;
    }

    /** @return the Configuration Layer of the batch (for tests and diagnosis) */
    DifferentialDriveBatch configuration() {
        return drive;
    }
}
