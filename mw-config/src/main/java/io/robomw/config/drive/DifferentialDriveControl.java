package io.robomw.config.drive;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.spi.CommandPriority;
import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.kinematics.DifferentialKinematics;
import io.robomw.config.kinematics.WheelMotion;

import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The Configuration Layer's first implementation (the paper's, for the LEGO and fischertechnik
 * bricks): a robot on two driven wheels moves by wheel motor rotations, which
 * {@link DifferentialKinematics} computes from the description's geometry; each motion is one
 * {@link MotorCommand} on both wheels. Wheel speeds are checked against {@code drive.max_speed}
 * before anything is sent. When both wheel motors have encoders, the pose is odometry from their
 * readings, kept by a {@link WheelOdometry} that listens to the motions this drive reports; without
 * encoders the robot still moves, timed, and has no pose.
 *
 * <p>Everything a verb needs of the description (its kinematics, ports, watchdog, whether it may
 * drive on the ground, whether the platform has the encoders) is worked out once, when the drive
 * is chosen for a description: {@code drive} comes ten times a second from a controller, and
 * costs no more than the command it sends. Thread-safe.
 */
public final class DifferentialDriveControl implements DriveControl {

    private final RobotDescription description;
    private final DifferentialKinematics kinematics;
    private final RobotPlatform platform;
    private final String left;
    private final String right;
    private final Duration watchdog;
    /** Why it cannot drive at all (a robot that is not a ground one), or {@code null}. */
    private final String cannotDrive;
    /** The pose from the encoders, or {@code null} if a wheel motor has none. */
    private final WheelOdometry odometry;
    /** Hears of every motion: the odometry, or nobody. */
    private final MotionListener listener;
    /** Numbers the motions, across reloads. */
    private final AtomicLong movements;
    /** The last {@code drive} command made (a value, so any thread may reuse it). */
    private volatile MotorCommand lastDrive;

    /**
     * @param description the description in force
     * @param drive       its differential drive
     * @param platform    the opened platform
     * @param previous    the drive chosen for the description before (a reload), whose pose
     *                    carries over, or {@code null}
     */
    DifferentialDriveControl(RobotDescription description, DifferentialDrive drive, RobotPlatform platform, DifferentialDriveControl previous) {
        this.description = description;
        this.kinematics = previous != null && previous.kinematics.drive().equals(drive) ? previous.kinematics : new DifferentialKinematics(drive);
        this.platform = platform;
        this.left = drive.left().port();
        this.right = drive.right().port();
        this.watchdog = description.watchdogTimeout();
        this.cannotDrive = description.capabilities().contains(Capability.GROUND) ? null
                : "it is a " + description.capabilities() + " robot, not a GROUND one";
        boolean encoders = platform.hasEncoder(left) && platform.hasEncoder(right);
        if (!encoders) {
            this.odometry = null;
        } else if (previous != null && previous.odometry != null && previous.left.equals(left) && previous.right.equals(right)) {
            previous.odometry.continueWith(kinematics);
            this.odometry = previous.odometry;
        } else {
            this.odometry = new WheelOdometry(platform, kinematics);
        }
        this.listener = odometry != null ? odometry : MotionListener.NONE;
        this.movements = previous != null ? previous.movements : new AtomicLong();
    }

    @Override
    public RobotDescription description() {
        return description;
    }

    @Override
    public CompletableFuture<Void> move(double distance, double speed) {
        Call call = call("move(%.3f, %.3f)", distance, speed);
        call.finite(distance, "distance");
        requireWheelSpeed(call, call.positive(speed, "speed"));
        return runWheels(call, kinematics.move(distance, speed), Math.signum(distance) * speed, 0, Math.abs(distance) / speed);
    }

    @Override
    public CompletableFuture<Void> turn(double radians, double speed) {
        Call call = call("turn(%.4f, %.4f)", radians, speed);
        call.finite(radians, "angle");
        requireWheelSpeed(call, call.positive(speed, "angular speed") * kinematics.drive().trackWidth() / 2);
        return runWheels(call, kinematics.turn(radians, speed), 0, Math.signum(radians) * speed, Math.abs(radians) / speed);
    }

    @Override
    public CompletableFuture<Void> arc(double radius, double angle, double speed) {
        Call call = call("arc(%.3f, %.4f, %.3f)", radius, angle, speed);
        call.finite(radius, "radius");
        call.finite(angle, "angle");
        call.positive(speed, "speed");
        WheelMotion m = kinematics.arc(radius, angle, speed);
        requireWheelSpeed(call, Math.max(m.leftDegreesPerSecond(), m.rightDegreesPerSecond()) / kinematics.motorDegreesPerMetre());
        if (radius == 0) {
            double rate = speed / (kinematics.drive().trackWidth() / 2); // on the spot, speed is each wheel's
            return runWheels(call, m, 0, Math.signum(angle) * rate, Math.abs(angle) / rate);
        }
        double linear = Math.signum(angle) * speed;
        return runWheels(call, m, linear, linear / radius, Math.abs(radius * angle) / speed);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        Call call = call("drive");
        call.finite(linearSpeed, "linear speed");
        call.finite(angularSpeed, "angular speed");
        WheelMotion m = kinematics.velocity(linearSpeed, angularSpeed);
        requireWheelSpeed(call, Math.max(Math.abs(m.leftDegreesPerSecond()), Math.abs(m.rightDegreesPerSecond())) / kinematics.motorDegreesPerMetre());
        listener.motionStarted(new Movement(movements.incrementAndGet(), linearSpeed, angularSpeed, Double.POSITIVE_INFINITY));
        // Nobody waits for a drive's completion: the platform need not make a future for it.
        platform.runDetached(driveCommand(m.leftDegreesPerSecond(), m.rightDegreesPerSecond()));
    }

    /**
     * @return the {@code drive} command for these wheel speeds: the last one when it asked for the
     *         same (a controller refreshing its drive at every tick often does), so a repeated drive
     *         makes no command, targets and list of its own (commands are values: nothing keeps or
     *         changes them)
     */
    private MotorCommand driveCommand(double leftSpeed, double rightSpeed) {
        MotorCommand last = lastDrive;
        if (last != null && Double.compare(last.targets().get(0).degreesPerSecond(), leftSpeed) == 0
                && Double.compare(last.targets().get(1).degreesPerSecond(), rightSpeed) == 0) {
            return last;
        }
        MotorCommand command = new MotorCommand("drive", List.of(MotorTarget.run(left, leftSpeed), MotorTarget.run(right, rightSpeed)),
                CommandPriority.NORMAL, watchdog);
        lastDrive = command;
        return command;
    }

    @Override
    public void halted() {
        listener.halted();
    }

    @Override
    public Pose pose() {
        return odometry("pose()").pose();
    }

    @Override
    public void resetPose(Pose pose) {
        odometry("resetPose()").reset(pose);
    }

    private WheelOdometry odometry(String call) {
        if (odometry == null) {
            throw new Call(description.name(), call).refused("its wheel motors have no encoders");
        }
        return odometry;
    }

    /** @return the call, after checking that the robot may drive at all */
    private Call call(String format, Object... args) {
        Call call = args.length == 0 ? new Call(description.name(), format) : Call.of(description.name(), format, args);
        if (cannotDrive != null) {
            throw call.refused(cannotDrive);
        }
        return call;
    }

    private void requireWheelSpeed(Call call, double metresPerSecond) {
        call.atMost(metresPerSecond, kinematics.drive().maxSpeed(), "wheel speed", "m/s", "drive.max_speed");
    }

    /**
     * Reports the motion started, hands its command to the platform, and has the listener hear of
     * its end.
     *
     * @param linear  metres per second of the robot's centre, signed
     * @param angular radians per second, signed
     * @param seconds how long it takes at speed
     */
    private CompletableFuture<Void> runWheels(Call call, WheelMotion m, double linear, double angular, double seconds) {
        Movement movement = new Movement(movements.incrementAndGet(), linear, angular, seconds);
        listener.motionStarted(movement);
        CompletableFuture<Void> done = platform.run(MotorCommand.of(call.text(), List.of(
                MotorTarget.rotate(left, m.leftDegrees(), m.leftDegreesPerSecond()),
                MotorTarget.rotate(right, m.rightDegrees(), m.rightDegreesPerSecond()))));
        return listener.endOf(done, movement);
    }
}
