package io.robomw.console.rosbridge.protocol;

import java.util.Arrays;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;

/**
 * The operations a client may send (a message's {@code op}), as rosbridge_suite's ROS 2 protocol
 * names them. The ones this bridge does not carry out are known, so a client is told they are not
 * offered rather than that they do not exist.
 */
enum Op {
    /** Announce publishing on a topic. */
    ADVERTISE("advertise", true),
    /** Stop publishing on a topic. */
    UNADVERTISE("unadvertise", true),
    /** Publish a message. */
    PUBLISH("publish", true),
    /** Receive a topic's messages. */
    SUBSCRIBE("subscribe", true),
    /** Stop receiving them. */
    UNSUBSCRIBE("unsubscribe", true),
    /** Call a service; answered with {@code service_response}. */
    CALL_SERVICE("call_service", true),
    /** One piece of a message sent in fragments. */
    FRAGMENT("fragment", true),
    /** Ask for {@code status} messages at a level (the ROS 1 protocol's; ROS 2's server has none). */
    SET_LEVEL("set_level", true),
    /** Offer a service from the client: not carried out. */
    ADVERTISE_SERVICE("advertise_service", false),
    /** Not carried out. */
    UNADVERTISE_SERVICE("unadvertise_service", false),
    /** A client's answer to a call of its service: not carried out. */
    SERVICE_RESPONSE("service_response", false),
    /** ROS 2 actions: not carried out. */
    ADVERTISE_ACTION("advertise_action", false),
    /** Not carried out. */
    UNADVERTISE_ACTION("unadvertise_action", false),
    /** Not carried out. */
    SEND_ACTION_GOAL("send_action_goal", false),
    /** Not carried out. */
    CANCEL_ACTION_GOAL("cancel_action_goal", false),
    /** Not carried out. */
    ACTION_FEEDBACK("action_feedback", false),
    /** Not carried out. */
    ACTION_RESULT("action_result", false);

    private static final Map<String, Op> BY_WIRE = Arrays.stream(values()).collect(Collectors.toUnmodifiableMap(Op::wire, Function.identity()));

    private final String wire;
    private final boolean offered;

    Op(String wire, boolean offered) {
        this.wire = wire;
        this.offered = offered;
    }

    /** @return its name on the wire */
    String wire() {
        return wire;
    }

    /** @return whether this bridge carries it out */
    boolean offered() {
        return offered;
    }

    /**
     * @param wire a message's op
     * @return the operation, or {@code null} if there is none of that name
     */
    static Op of(String wire) {
        return BY_WIRE.get(wire);
    }

    /** @return the names of the operations this bridge carries out, as an error lists them */
    static String allowed() {
        return Arrays.stream(values()).filter(Op::offered).map(Op::wire).collect(Collectors.joining(", ", "[", "]"));
    }
}
