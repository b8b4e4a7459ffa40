package io.robomw.api.spi;

import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import io.robomw.api.Message;
import io.robomw.api.MessageListener;
import io.robomw.api.UnsupportedActionException;

import java.io.Serializable;
import java.time.Duration;
import java.util.List;
import java.util.Optional;
import java.util.ServiceLoader;
import java.util.UUID;

/**
 * Finds the providers that give every robot its communication component and its agency
 * ({@link MessagingProvider}, {@link AgencyProvider}, through {@link ServiceLoader}), so that the
 * Configuration Layer and the simulator link the paper's four components without compiling
 * against {@code mw-agents}. Without a provider on the class path a robot still moves and senses,
 * and its messaging or agency calls throw {@link UnsupportedActionException} saying which
 * artifact adds them.
 */
public final class RobotComponents {

    private static final String ADD_AGENTS = "add io.robomw:mw-agents to the class path (the mw distribution has it)";

    private RobotComponents() {
    }

    /**
     * @param robotName the robot, for error messages
     * @param config    its messaging settings
     * @return its communication component from the first provider found, or one that refuses every call
     */
    public static MessagingComponent messaging(String robotName, MessagingConfig config) {
        return ServiceLoader.load(MessagingProvider.class, RobotComponents.class.getClassLoader()).findFirst()
                .map(p -> p.open(config))
                .orElseGet(() -> new Absent(robotName, "no messaging provider is on the class path; " + ADD_AGENTS));
    }

    /**
     * @param robotName the robot, for error messages
     * @param config    its agency settings
     * @return its agency from the first provider found, or one that refuses every call
     */
    public static AgencyComponent agency(String robotName, AgencyConfig config) {
        return ServiceLoader.load(AgencyProvider.class, RobotComponents.class.getClassLoader()).findFirst()
                .map(p -> p.open(config))
                .orElseGet(() -> new Absent(robotName, "no agent runtime is on the class path; " + ADD_AGENTS));
    }

    /** The component of a robot that has none: every call says why. */
    private record Absent(String robot, String why) implements MessagingComponent, AgencyComponent {

        private UnsupportedActionException refuse(String action) {
            return new UnsupportedActionException(robot, action, why);
        }

        @Override
        public List<String> addresses() {
            return List.of();
        }

        @Override
        public Optional<String> homeAddress() {
            return Optional.empty();
        }

        @Override
        public UUID sendMessage(String name, String host, String pass, String topic, Serializable object, String function) {
            throw refuse("sendMessage");
        }

        @Override
        public Message waitForReply(String topic, String host) {
            throw refuse("waitForReply");
        }

        @Override
        public Message waitForReply(String topic, String host, Duration timeout) {
            throw refuse("waitForReply");
        }

        @Override
        public Message waitForReply(UUID correlationId, Duration timeout) {
            throw refuse("waitForReply");
        }

        @Override
        public void replyMessage(Message request, Serializable object, String function) {
            throw refuse("replyMessage");
        }

        @Override
        public void publishMessage(String topic, Serializable object, String function, String password) {
            throw refuse("publishMessage");
        }

        @Override
        public void subscribeMessage(String topic, String password) {
            throw refuse("subscribeMessage");
        }

        @Override
        public void addMessageListener(String topic, String password, MessageListener listener) {
            throw refuse("addMessageListener");
        }

        @Override
        public void removeMessageListener(String topic, MessageListener listener) {
            throw refuse("removeMessageListener");
        }

        @Override
        public AgentRef sendAgent(String host, Agent agent) {
            throw refuse("sendAgent");
        }

        @Override
        public AgentRef startTrip(Agent agent) {
            throw refuse("startTrip");
        }

        @Override
        public List<AgentRef> dispatchClones(Agent agent, String... hosts) {
            throw refuse("dispatchClones");
        }

        @Override
        public void close() {
        }
    }
}
