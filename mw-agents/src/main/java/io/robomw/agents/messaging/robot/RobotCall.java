package io.robomw.agents.messaging.robot;

import io.robomw.api.Futures;
import io.robomw.api.Pose;
import io.robomw.api.Position;
import io.robomw.api.ReturnType;
import io.robomw.api.Robot;
import io.robomw.api.SensorType;

import java.io.Serializable;
import java.time.Duration;
import java.util.ArrayList;
import java.util.concurrent.CompletableFuture;

/**
 * One call of a remote robot's verbs, as it travels from {@link RemoteRobot} to
 * {@link RobotServer}. Each call knows how to run itself on the served robot and how long it may
 * take (so the client's wait is bounded by the motion, not by a guess). A motion's future keeps
 * the verbs' contract: cancelling it ends the robot's command, which is what {@link Cancel} does
 * for a caller whose wait ended early.
 */
public sealed interface RobotCall extends Serializable {

    /**
     * Runs the call on the served robot.
     *
     * @param robot the robot
     * @return completes with the result (a {@code Double}, {@code double[]} pose, {@link RobotInfo} or {@code null})
     */
    CompletableFuture<Serializable> run(Robot robot);

    /** @return how long the motion itself should take; the client adds its reply timeout */
    default Duration expectedDuration() {
        return Duration.ZERO;
    }

    /** Asks for the robot's name, capabilities, sensors and actions. */
    record Describe() implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return CompletableFuture.completedFuture(RobotInfo.of(robot));
        }
    }

    /** {@link Robot#moveAsync}. @param distance metres @param speed m/s */
    record Move(double distance, double speed) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return motion(robot.moveAsync(distance, speed));
        }

        @Override
        public Duration expectedDuration() {
            return seconds(distance, speed);
        }
    }

    /** {@link Robot#turnAsync}. @param radians angle @param speed rad/s */
    record Turn(double radians, double speed) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return motion(robot.turnAsync(radians, speed));
        }

        @Override
        public Duration expectedDuration() {
            return seconds(radians, speed);
        }
    }

    /** {@link Robot#arcAsync}. @param radius metres @param angle radians @param speed m/s */
    record Arc(double radius, double angle, double speed) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return motion(robot.arcAsync(radius, angle, speed));
        }

        @Override
        public Duration expectedDuration() {
            return seconds(radius * angle, speed);
        }
    }

    /**
     * Ends a call still running on the served robot (a motion whose caller's wait ended early:
     * interrupted, or past its deadline): the motion's future is cancelled, so its command ends
     * and its motors brake. The result is whether the call was still running.
     *
     * @param call the correlation id of the call to end
     */
    record Cancel(java.util.UUID call) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            throw new IllegalStateException("a cancel is handled by the robot's server, which knows its running calls");
        }
    }

    /** {@link Robot#drive}. @param linearSpeed m/s @param angularSpeed rad/s */
    record Drive(double linearSpeed, double angularSpeed) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            robot.drive(linearSpeed, angularSpeed);
            return CompletableFuture.completedFuture(null);
        }
    }

    /** {@link Robot#stop}. */
    record Stop() implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            robot.stop();
            return CompletableFuture.completedFuture(null);
        }
    }

    /** {@link Robot#changeAltitudeAsync}. @param metres climb @param speed m/s */
    record ChangeAltitude(double metres, double speed) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return motion(robot.changeAltitudeAsync(metres, speed));
        }

        @Override
        public Duration expectedDuration() {
            return seconds(metres, speed);
        }
    }

    /** {@link Robot#performAsync}. @param action the action @param args its arguments */
    record Perform(String action, double[] args) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return motion(robot.performAsync(action, args));
        }
    }

    /** {@link Robot#getValueAsync(Position, SensorType, ReturnType)}. @param position where @param type what @param returnType unit */
    record GetValue(Position position, SensorType type, ReturnType returnType) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return robot.getValueAsync(position, type, returnType).thenApply(v -> v);
        }
    }

    /** {@link Robot#getValueAsync(String, ReturnType)}. @param sensorName the sensor @param returnType unit */
    record GetValueByName(String sensorName, ReturnType returnType) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            return robot.getValueAsync(sensorName, returnType).thenApply(v -> v);
        }
    }

    /** {@link Robot#pose()}; the result is {@code double[] {x, y, heading}}. */
    record GetPose() implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            Pose p = robot.pose();
            return CompletableFuture.completedFuture(new double[] {p.x(), p.y(), p.heading()});
        }
    }

    /** {@link Robot#resetPose}. @param x metres @param y metres @param heading radians */
    record ResetPose(double x, double y, double heading) implements RobotCall {
        @Override
        public CompletableFuture<Serializable> run(Robot robot) {
            robot.resetPose(new Pose(x, y, heading));
            return CompletableFuture.completedFuture(null);
        }
    }

    /** @return a motion's future as a call's result, cancelling which cancels the motion's own (its command ends) */
    private static CompletableFuture<Serializable> motion(CompletableFuture<Void> command) {
        return Futures.cancelling(command.thenApply(v -> null), command);
    }

    private static Duration seconds(double amount, double speed) {
        double s = speed > 0 && Double.isFinite(amount) ? Math.abs(amount) / speed : 0;
        return Duration.ofNanos((long) Math.min(s * 1e9, 3.6e12));
    }

    /** @return the classes of every call, for the server's allow-list */
    static java.util.List<Class<?>> classes() {
        java.util.List<Class<?>> out = new ArrayList<>();
        for (Class<?> c : RobotCall.class.getPermittedSubclasses()) {
            out.add(c);
        }
        out.addAll(java.util.List.of(Position.class, SensorType.class, ReturnType.class));
        return out;
    }
}
