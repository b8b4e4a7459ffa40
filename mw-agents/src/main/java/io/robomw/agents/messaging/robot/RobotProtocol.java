package io.robomw.agents.messaging.robot;

import io.robomw.agents.messaging.MessagingSettings;

import java.util.ArrayList;
import java.util.List;

/**
 * What the remote-robot protocol needs from messaging: the topic of a served robot, and the
 * payload classes each side must allow.
 */
public final class RobotProtocol {

    /** Topic prefix; a robot named {@code nxt-1} is served on {@code robot/nxt-1}. */
    public static final String TOPIC_PREFIX = "robot/";
    /** The function of every call. */
    public static final String CALL = "call";

    private RobotProtocol() {
    }

    /**
     * @param robotName a robot's name
     * @return the topic it is served on
     */
    public static String topic(String robotName) {
        return TOPIC_PREFIX + robotName;
    }

    /**
     * @param settings a server's settings
     * @return them, with the calls on the allow-list
     */
    public static MessagingSettings forServer(MessagingSettings settings) {
        return settings.allowPayloadTypes(RobotCall.classes().toArray(Class<?>[]::new));
    }

    /**
     * @param settings a client's settings
     * @return them, with replies, robot descriptions and the travelling exceptions on the allow-list
     */
    public static MessagingSettings forClient(MessagingSettings settings) {
        List<Class<?>> types = new ArrayList<>(RobotInfo.classes());
        types.add(RobotReply.class);
        types.addAll(RobotFailures.TRAVELLING);
        return settings.withAllowList(settings.allowList().with(types.toArray(Class<?>[]::new)).withNames(RobotFailures.INTERNALS));
    }
}
