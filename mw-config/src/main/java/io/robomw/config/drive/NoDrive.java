package io.robomw.config.drive;

import io.robomw.api.Pose;
import io.robomw.config.description.RobotDescription;

import java.util.concurrent.CompletableFuture;

/**
 * The drive of a robot whose description has none (an arm, a sensor station): every motion and
 * the pose are refused, saying so; a stop has nothing to end.
 *
 * @param description the description in force
 */
record NoDrive(RobotDescription description) implements DriveControl {

    private static final String REASON = "its description has no drive";

    @Override
    public CompletableFuture<Void> move(double distance, double speed) {
        throw Call.of(description.name(), "move(%.3f, %.3f)", distance, speed).refused(REASON);
    }

    @Override
    public CompletableFuture<Void> turn(double radians, double speed) {
        throw Call.of(description.name(), "turn(%.4f, %.4f)", radians, speed).refused(REASON);
    }

    @Override
    public CompletableFuture<Void> arc(double radius, double angle, double speed) {
        throw Call.of(description.name(), "arc(%.3f, %.4f, %.3f)", radius, angle, speed).refused(REASON);
    }

    @Override
    public void drive(double linearSpeed, double angularSpeed) {
        throw new Call(description.name(), "drive").refused(REASON);
    }

    @Override
    public void halted() {
        // nothing moves
    }

    @Override
    public Pose pose() {
        throw new Call(description.name(), "pose()").refused(REASON + " to estimate a pose from");
    }

    @Override
    public void resetPose(Pose pose) {
        throw new Call(description.name(), "resetPose()").refused(REASON + " to estimate a pose from");
    }
}
