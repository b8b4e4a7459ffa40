package io.robomw.api;

import java.util.List;
import java.util.Set;

/**
 * One robot, as the Instruction Layer of the paper "A robotic middleware" sees it: it can move
 * ({@link Motion}), sense ({@link Perception}), exchange messages ({@link Messaging}) and send
 * mobile agents ({@link Agency}).
 *
 * <p>A {@code Robot} is the same interface whatever is underneath: a LEGO or fischertechnik
 * brick on a serial link, a simulated robot, or a robot on another host reached over the
 * network. What the robot can do is read from its description; an action it cannot do raises
 * {@link UnsupportedActionException} naming the robot and the action, before anything moves.
 *
 * <p>Thread safety: every method may be called from any thread. Motion commands on the same
 * actuators follow the "most recent command wins" rule: a newer command interrupts an older one,
 * whose caller gets {@link CommandPreemptedException}.
 *
 * <p>A robot holds a link to its hardware; {@link #close()} stops the motors and releases it.
 */
public interface Robot extends Motion, Perception, Messaging, Agency, AutoCloseable {

    /** @return the robot's name, as given in its description; unique among the robots of a program */
    String name();

    /** @return what kinds of motion this robot is built for (ground, air, water) */
    Set<Capability> capabilities();

    /**
     * @param capability a capability
     * @return whether this robot has it
     */
    default boolean can(Capability capability) {
        return capabilities().contains(capability);
    }

    /** @return the sensors this robot has, in the order of its description */
    List<SensorInfo> sensors();

    /**
     * @return the named actions of its extra actuators ({@code "gripper.open"}...) and the
     *         high-level actions its firmware performs ({@code "sit"}, {@code "head.pan"}), usable
     *         with {@link #perform}
     */
    List<String> actions();

    /** Stops every motor and releases the link to the hardware. Idempotent. */
    @Override
    void close();
}
