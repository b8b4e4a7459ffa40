package io.robomw.agents.host;

import io.robomw.api.Robot;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.concurrent.locks.ReentrantLock;

/**
 * Who drives a host's robot: one agent's stop at a time, in the order they asked (a fair lock),
 * so two agents' moves never pre-empt each other. A stop takes the robot when it first asks for
 * it and gives it back when its work returns.
 */
final class RobotTurns {

    private static final Logger LOG = LoggerFactory.getLogger(RobotTurns.class);

    private final String hostName;
    private final Robot robot;
    private final ReentrantLock lock = new ReentrantLock(true);

    /** @param robot the host's robot, or {@code null} if it has none */
    RobotTurns(String hostName, Robot robot) {
        this.hostName = hostName;
        this.robot = robot;
    }

    /**
     * Takes the robot for the calling agent's stop (waiting for the agent that has it), unless it already has it.
     *
     * @return the robot, or {@code null} if the host has none
     */
    Robot claim(HostedAgent h) {
        if (robot != null && !lock.isHeldByCurrentThread()) {
            if (!lock.tryLock()) {
                LOG.info("host {}: agent {} waits for the robot, which another agent's stop is using", hostName, h.id);
                try {
                    lock.lockInterruptibly();
                } catch (InterruptedException e) {
                    // a retract or dispose: the agent stops waiting for the robot
                    Thread.currentThread().interrupt();
                    throw new io.robomw.api.RobotException("agent " + h.id + " was interrupted waiting for the robot of host " + hostName
                            + " (a retract or dispose)", e);
                }
            }
        }
        return robot;
    }

    /** Gives the robot back, if the calling stop has it. */
    void release() {
        while (lock.isHeldByCurrentThread()) {
            lock.unlock();
        }
    }
}
