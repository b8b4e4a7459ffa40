package io.robomw.api.spi;

import io.robomw.api.Clock;

import java.util.concurrent.CompletableFuture;

/**
 * A robot platform that takes {@link HighLevelCommand}s: the firmware's own walking and posture
 * commands (a Sony Aibo over URBI), rather than motor rotations. It is the Platform Layer half of
 * the paper's second Configuration Layer implementation, which "rather than calculating distances
 * for the legs to move, accesses the high level Aibo commands to move the robot through the
 * Platform Layer".
 *
 * <p>Optional: a {@link RobotPlatform} implements this as well when it can; every other platform
 * is unchanged. The Configuration Layer uses it for robots whose description has a legged drive,
 * and refuses their motions on a platform that does not implement it.
 *
 * <p>Thread safety: {@link #execute} may be called from any thread and returns at once; the
 * command runs on the platform's execution action thread under its clash, priority and watchdog
 * rules (see {@link HighLevelCommand}). {@link RobotPlatform#stopAll()} ends every running
 * high-level command, each with its stop.
 */
public interface HighLevelPlatform {

    /**
     * Runs a high-level command. Returns at once.
     *
     * @param command the command
     * @return completes when the platform reports the command done; fails with
     *         {@link io.robomw.api.CommandPreemptedException} when a newer command takes one of its
     *         actuators (or it was refused, its actuators being held by a command it may not
     *         interrupt), with a {@link io.robomw.api.RobotException} naming the command when the
     *         robot reports an error for it, it runs far over its expected duration or its
     *         watchdog expires, and with {@link io.robomw.api.RobotLinkException} when the link
     *         fails
     */
    CompletableFuture<Void> execute(HighLevelCommand command);

    /**
     * @return the clock the platform's execution action thread runs on, so that the layer above
     *         can time what it commanded (dead reckoning) on the same time base: the wall clock for a
     *         real robot, the simulated clock in a simulation
     */
    Clock clock();
}
