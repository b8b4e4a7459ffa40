package io.robomw.api;

import java.io.Serializable;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.UUID;

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
 * <p>The paper's four components are linked here: motion and perception are the robot's own;
 * its messaging calls go to its communication component ({@link #messaging()}) and its agency
 * calls to its agency ({@link #agency()}), so a program writes {@code robot.sendMessage(...)} or
 * {@code robot.sendAgent(...)} as in the paper, and an implementation gives the two components
 * rather than forwarding each call.
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

    /**
     * @return the robot's communication component, which its {@link Messaging} calls go to; one
     *         that throws {@link UnsupportedActionException} from every call if it has none
     */
    Messaging messaging();

    /**
     * @return the robot's agency, which its {@link Agency} calls go to; one that throws
     *         {@link UnsupportedActionException} from every call if it has none
     */
    Agency agency();

    @Override
    default UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function) {
        return messaging().sendMessage(name, host, pass, topic, object, function);
    }

    @Override
    default Message waitForReply(String topic, String host) {
        return messaging().waitForReply(topic, host);
    }

    @Override
    default Message waitForReply(String topic, String host, Duration timeout) {
        return messaging().waitForReply(topic, host, timeout);
    }

    @Override
    default Message waitForReply(UUID correlationId, Duration timeout) {
        return messaging().waitForReply(correlationId, timeout);
    }

    @Override
    default void replyMessage(Message request, Serializable object, String function) {
        messaging().replyMessage(request, object, function);
    }

    @Override
    default void publishMessage(String topic, Serializable object, String function, String password) {
        messaging().publishMessage(topic, object, function, password);
    }

    @Override
    default void subscribeMessage(String topic, String password) {
        messaging().subscribeMessage(topic, password);
    }

    @Override
    default void addMessageListener(String topic, String password, MessageListener listener) {
        messaging().addMessageListener(topic, password, listener);
    }

    @Override
    default void removeMessageListener(String topic, MessageListener listener) {
        messaging().removeMessageListener(topic, listener);
    }

    @Override
    default AgentRef sendAgent(String host, Agent agent) {
        return agency().sendAgent(host, agent);
    }

    @Override
    default AgentRef startTrip(Agent agent) {
        return agency().startTrip(agent);
    }

    @Override
    default List<AgentRef> dispatchClones(Agent agent, String... hosts) {
        return agency().dispatchClones(agent, hosts);
    }

    /** Stops every motor and releases the link to the hardware. Idempotent. */
    @Override
    void close();
}
