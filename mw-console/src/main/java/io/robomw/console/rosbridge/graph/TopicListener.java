package io.robomw.console.rosbridge.graph;

/**
 * Receives a topic's publications: a client's subscription, or a sink inside the bridge (a
 * robot's {@code cmd_vel}, a RoboMW messaging topic). Called on the publishing thread; must not
 * block (hand work on, or drop it).
 */
@FunctionalInterface
public interface TopicListener {

    /** @param publication the message */
    void deliver(Publication publication);
}
