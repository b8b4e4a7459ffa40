package io.robomw.config.drive;

import io.robomw.api.Capability;
import io.robomw.api.Pose;
import io.robomw.api.UnsupportedActionException;
import io.robomw.config.description.RobotDescription;

import java.util.concurrent.CompletableFuture;

/**
 * How one robot moves, for one description in force: the Configuration Layer's half of the
 * Instruction Layer's {@link io.robomw.api.Motion}. Each kind of drive in a robot file has one
 * implementation ({@link Drives#choose} picks it): a differential drive turns motions into wheel
 * rotations, a legged drive into its firmware's walking commands; a vehicle drive (position, yaw
 * and velocity targets for an autopilot) is the third. The robot reads the description in force
 * once per verb and, when a reload brought a new one, has the drive chosen again; the verbs never
 * ask which kind of drive they have.
 *
 * <h2>Contract of every implementation</h2>
 * <ul>
 *   <li>Units and signs are {@link io.robomw.api.Motion}'s: metres, radians, seconds; a positive
 *   distance drives forwards, a positive angle turns left.</li>
 *   <li>Every check happens before anything is sent: a motion the robot cannot do, or whose
 *   arguments break a limit of its description, throws {@link UnsupportedActionException} naming
 *   the robot, the call, the value and the rule ({@link Call}).</li>
 *   <li>The motion verbs return at once. Their future completes when the motion is done, and
 *   keeps the Instruction Layer's cancel contract: cancelling it cancels the platform's command
 *   (its motors brake), also when it is derived from the platform's future
 *   ({@link io.robomw.api.Futures#cancelling}).</li>
 *   <li>A drive tells its pose tracker of the motions it commands ({@link MotionListener}); the
 *   tracker integrates on the threads that ask for the pose, never on the platform's action
 *   thread.</li>
 *   <li>Thread-safe: any thread may call any method.</li>
 * </ul>
 */
public interface DriveControl {

    /** @return the description it was chosen for */
    RobotDescription description();

    /**
     * Straight ahead: wheel rotations, a walk, or a position target {@code distance} ahead in the
     * body frame.
     *
     * @param distance metres, negative backwards
     * @param speed    metres per second, &gt; 0
     * @return completes when the motion is done
     */
    CompletableFuture<Void> move(double distance, double speed);

    /**
     * On the spot: a turn of the wheels or the legs, or a yaw target.
     *
     * @param radians positive turns left
     * @param speed   radians per second, &gt; 0
     * @return completes when the turn is done
     */
    CompletableFuture<Void> turn(double radians, double speed);

    /**
     * Along a circular arc.
     *
     * @param radius metres from the arc's centre to the robot's centre, positive centre on the left
     * @param angle  radians of arc, positive forwards
     * @param speed  metres per second of the robot's centre, &gt; 0
     * @return completes when the arc is done
     */
    CompletableFuture<Void> arc(double radius, double angle, double speed);

    /**
     * At velocities until told otherwise: a continuous command, stopped by the platform unless
     * repeated within the description's watchdog timeout. Returns at once.
     *
     * @param linearSpeed  metres per second, negative backwards
     * @param angularSpeed radians per second, positive left
     */
    void drive(double linearSpeed, double angularSpeed);

    /**
     * Climbs or descends. Only a drive that flies can; the default refuses, saying why.
     *
     * @param metres positive climbs
     * @param speed  metres per second, &gt; 0
     * @return completes when the altitude is reached
     * @throws UnsupportedActionException if it cannot fly
     */
    default CompletableFuture<Void> changeAltitude(double metres, double speed) {
        throw cannotFly(Call.of(description().name(), "changeAltitude(%.3f, %.3f)", metres, speed));
    }

    /**
     * Takes off and climbs to an altitude above its take-off point. Only a drive that flies can; the
     * default refuses, saying why.
     *
     * @param altitude metres above the take-off point, &gt; 0
     * @return completes when the altitude is reached
     * @throws UnsupportedActionException if it cannot fly
     */
    default CompletableFuture<Void> takeOff(double altitude) {
        throw cannotFly(Call.of(description().name(), "takeOff(%.3f)", altitude));
    }

    /**
     * Lands where it is. Only a drive that flies can; the default refuses, saying why.
     *
     * @return completes when it has landed
     * @throws UnsupportedActionException if it cannot fly
     */
    default CompletableFuture<Void> land() {
        throw cannotFly(new Call(description().name(), "land()"));
    }

    /**
     * The robot's motors were stopped (its stop was handed to the hardware): the motion under way
     * has ended now, for the pose. Cheap; called on the thread that stopped the robot.
     */
    void halted();

    /**
     * @return the pose estimate now, relative to where the robot was opened or last reset
     * @throws UnsupportedActionException if this drive cannot estimate one (wheels without encoders)
     */
    Pose pose();

    /**
     * @param pose the robot's pose now; what it does next is integrated from it
     * @throws UnsupportedActionException if this drive cannot estimate a pose
     */
    void resetPose(Pose pose);

    /**
     * The refusal of a flying verb by a drive that does not fly: a robot that is not
     * {@link Capability#AIR} cannot, and an air robot whose drive has no altitude control cannot
     * either.
     *
     * @param call the call
     * @return the exception to throw
     */
    private UnsupportedActionException cannotFly(Call call) {
        RobotDescription d = description();
        if (!d.capabilities().contains(Capability.AIR)) {
            return call.refused("it is a " + d.capabilities() + " robot, not an AIR one");
        }
        return call.refused("platform '" + d.platform() + "' has no altitude control");
    }
}
