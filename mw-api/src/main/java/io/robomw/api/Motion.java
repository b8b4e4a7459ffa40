package io.robomw.api;

import java.util.concurrent.CompletableFuture;

/**
 * Driving and the robot's other actuators.
 *
 * <p>Units: metres, radians, seconds. A positive distance drives forwards, a positive angle turns
 * left (anti-clockwise), increasing the heading. Speeds are magnitudes and must be positive.
 *
 * <p>Each verb comes in two forms: the plain one blocks until the motion is complete; the
 * {@code ...Async} form returns at once, and its future completes when the motion does. A motion
 * interrupted by a newer command on the same motors ends with {@link CommandPreemptedException}
 * (thrown, or completing the future exceptionally). A robot whose link to the hardware fails ends
 * its motions with {@link RobotLinkException}.
 *
 * <h2>Deadlines, interrupts and cancelling</h2>
 * Every blocking form waits with a deadline: a motion three times its duration at the commanded
 * speed plus {@link Futures#MOTION_SLACK} ({@link Futures#motionTimeout}), a named action at most
 * {@link Futures#DEFAULT_TIMEOUT}. Cancelling the future of an {@code ...Async} form ends its
 * command: its motors brake at the platform's next cycle. A blocking form whose thread is
 * interrupted, or whose deadline passes, cancels its command that way and throws a
 * {@link RobotException} saying so (an interrupted thread keeps its interrupt status): a robot
 * does not drive on for a caller who stopped waiting.
 */
public interface Motion {

    /**
     * Drives straight. Blocks until the robot has covered the distance.
     *
     * @param distance metres; negative drives backwards
     * @param speed    metres per second, &gt; 0 and at most the robot's maximum
     * @throws UnsupportedActionException if the robot cannot drive, or the speed is above its maximum
     */
    default void move(double distance, double speed) {
        Futures.await(moveAsync(distance, speed), Futures.motionTimeout(Math.abs(distance) / speed), call("move", distance, speed));
    }

    /**
     * Starts driving straight and returns at once.
     *
     * @param distance metres; negative drives backwards
     * @param speed    metres per second, &gt; 0
     * @return completes when the robot has covered the distance
     * @throws UnsupportedActionException at once if the robot cannot do it
     */
    CompletableFuture<Void> moveAsync(double distance, double speed);

    /**
     * Turns on the spot. Blocks until the turn is complete.
     *
     * @param radians angle; positive turns left (anti-clockwise)
     * @param speed   angular speed in radians per second, &gt; 0
     */
    default void turn(double radians, double speed) {
        Futures.await(turnAsync(radians, speed), Futures.motionTimeout(Math.abs(radians) / speed), call("turn", radians, speed));
    }

    /**
     * Starts a turn on the spot and returns at once.
     *
     * @param radians angle; positive turns left (anti-clockwise)
     * @param speed   angular speed in radians per second, &gt; 0
     * @return completes when the turn is complete
     */
    CompletableFuture<Void> turnAsync(double radians, double speed);

    /**
     * Drives along a circular arc. Blocks until done.
     *
     * @param radius metres from the arc's centre to the robot's centre; positive centre on the left
     * @param angle  radians of arc to drive; positive drives forwards
     * @param speed  metres per second of the robot's centre, &gt; 0
     */
    default void arc(double radius, double angle, double speed) {
        Futures.await(arcAsync(radius, angle, speed), Futures.motionTimeout(Math.abs(radius * angle) / speed),
                call("arc", radius, angle, speed));
    }

    /**
     * Starts driving along an arc and returns at once.
     *
     * @param radius metres, positive centre on the left
     * @param angle  radians of arc
     * @param speed  metres per second of the robot's centre
     * @return completes when the arc is done
     */
    CompletableFuture<Void> arcAsync(double radius, double angle, double speed);

    /**
     * Drives continuously at the given velocities and returns at once. This is a continuous
     * command: it must be repeated within the robot's watchdog timeout (default 0.5 s) or the
     * motors stop by themselves, so a crashed program cannot leave a robot driving.
     *
     * @param linearSpeed  metres per second, negative backwards
     * @param angularSpeed radians per second, positive turns left
     */
    void drive(double linearSpeed, double angularSpeed);

    /**
     * Stops every motor at once. This command has safety priority: no normal command interrupts
     * it while it runs. Blocks until the stop has been handed to the hardware (written to its
     * link), a few seconds at most; once it returns, the robot's motions have ended and a new
     * command is taken as usual.
     *
     * @throws RobotLinkException naming the robot if the stop could not be handed to the hardware
     *                            (the link is down, or did not take it in time)
     */
    void stop();

    /**
     * Climbs or descends. Only robots with {@link Capability#AIR} can; every other robot throws.
     *
     * @param metres positive climbs
     * @param speed  metres per second, &gt; 0
     * @throws UnsupportedActionException if the robot cannot fly
     */
    default void changeAltitude(double metres, double speed) {
        Futures.await(changeAltitudeAsync(metres, speed), Futures.motionTimeout(Math.abs(metres) / speed),
                call("changeAltitude", metres, speed));
    }

    /**
     * Non-blocking form of {@link #changeAltitude}.
     *
     * @param metres positive climbs
     * @param speed  metres per second
     * @return completes when the altitude is reached
     */
    CompletableFuture<Void> changeAltitudeAsync(double metres, double speed);

    /**
     * Takes off and climbs to an altitude above the take-off point, then holds there. Only a robot
     * with {@link Capability#AIR} whose drive flies (a multirotor's vehicle drive) can; every other
     * robot throws before anything is sent. Blocks until the altitude is reached (waiting as for a
     * climb at 0.5 m/s).
     *
     * @param altitude metres above the take-off point, &gt; 0
     * @throws UnsupportedActionException if the robot cannot fly (a boat, a wheeled robot), or the
     *                                    altitude is out of its limits
     */
    default void takeOff(double altitude) {
        Futures.await(takeOffAsync(altitude), Futures.motionTimeout(Math.abs(altitude) / TAKE_OFF_AND_LANDING_SPEED), call("takeOff", altitude));
    }

    /**
     * Non-blocking form of {@link #takeOff}. The default refuses: a robot that flies overrides it.
     *
     * @param altitude metres above the take-off point
     * @return completes when the altitude is reached
     * @throws UnsupportedActionException at once if the robot cannot fly
     */
    default CompletableFuture<Void> takeOffAsync(double altitude) {
        throw new UnsupportedActionException(this instanceof Robot r ? r.name() : "this robot", call("takeOff", altitude), "it does not fly");
    }

    /**
     * Lands where it is (comes down at its autopilot's landing speed, then disarms). Only a robot
     * that flies can; every other robot throws before anything is sent. Blocks until it is on the
     * ground, at most {@link Futures#DEFAULT_TIMEOUT}.
     *
     * @throws UnsupportedActionException if the robot cannot fly
     */
    default void land() {
        Futures.await(landAsync(), Futures.DEFAULT_TIMEOUT, "land()");
    }

    /**
     * Non-blocking form of {@link #land}. The default refuses: a robot that flies overrides it.
     *
     * @return completes when the robot is on the ground
     * @throws UnsupportedActionException at once if the robot cannot fly
     */
    default CompletableFuture<Void> landAsync() {
        throw new UnsupportedActionException(this instanceof Robot r ? r.name() : "this robot", "land()", "it does not fly");
    }

    /** The speed, m/s, a blocking {@link #takeOff} allows for: its deadline is as for a climb at this speed. */
    double TAKE_OFF_AND_LANDING_SPEED = 0.5;

    /**
     * Runs a named action of an extra actuator (a gripper, an arm), as listed by
     * {@link Robot#actions()}, for example {@code perform("gripper.close")}, or a high-level action
     * of the robot's firmware ({@code perform("sit")}, {@code perform("head.pan", 0.5)}). Blocks
     * until done.
     *
     * @param action the action's name, {@code actuator.action}, or the high-level action's name
     * @param args   the action's arguments, if its description asks for any (for example an angle in radians)
     * @throws UnsupportedActionException if the robot has no such action, or the arguments do not fit it
     */
    default void perform(String action, double... args) {
        Futures.await(performAsync(action, args), Futures.DEFAULT_TIMEOUT, "perform(\"" + action + "\")");
    }

    /**
     * Non-blocking form of {@link #perform}.
     *
     * @param action the action's name
     * @param args   its arguments
     * @return completes when the action is done
     */
    CompletableFuture<Void> performAsync(String action, double... args);

    /**
     * @param verb the verb
     * @param args its arguments
     * @return the call as messages name it, {@code move(0.500, 0.200)}
     */
    private static String call(String verb, double... args) {
        StringBuilder b = new StringBuilder(verb).append('(');
        for (int i = 0; i < args.length; i++) {
            b.append(i == 0 ? "" : ", ").append(String.format(java.util.Locale.ROOT, "%.3f", args[i]));
        }
        return b.append(')').toString();
    }
}
