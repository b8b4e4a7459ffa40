package io.robomw.api.spi;

import java.util.List;
import java.util.Map;
import java.util.Objects;

/**
 * How a robot's communication component (the paper's messaging) is set up: the optional
 * {@code messaging:} section of its robot file, or the defaults.
 *
 * <p>With neither {@link #listen()} nor {@link #connect()} addresses the component starts on first
 * use, listening on loopback at an ephemeral port ({@link #DEFAULT_LISTEN}); with addresses given it
 * starts when the robot opens, so that peers can reach it, and it has their subscriptions, before
 * the robot's first messaging call.
 *
 * @param nodeName       the node's name: the sender name of its messages, and the receiver name
 *                       it answers to (by default the robot's name)
 * @param listen         where it receives, for example {@code tcp://127.0.0.1:7100}; empty for the default
 * @param connect        peers whose publications it wants (their subscriptions are kept up)
 * @param topicPasswords passwords of protected topics, by reference; a call that passes
 *                       {@code null} as the password of such a topic uses this one
 * @param source         where the settings came from (the robot file), for messages
 */
public record MessagingConfig(String nodeName, List<String> listen, List<String> connect,
                              Map<String, SecretRef> topicPasswords, String source) {

    /** Where a node without a {@code listen} setting receives: loopback, a port chosen at start. */
    public static final String DEFAULT_LISTEN = "tcp://127.0.0.1:0";

    /** Checks and copies. */
    public MessagingConfig {
        Objects.requireNonNull(source, "source");
        if (nodeName == null || nodeName.isBlank()) {
            throw new IllegalArgumentException(source + ": a messaging node needs a name");
        }
        listen = List.copyOf(listen);
        connect = List.copyOf(connect);
        topicPasswords = Map.copyOf(topicPasswords);
    }

    /**
     * @param robotName the robot's name
     * @param source    its file
     * @return the settings of a robot whose file has no {@code messaging:} section
     */
    public static MessagingConfig defaults(String robotName, String source) {
        return new MessagingConfig(robotName, List.of(), List.of(), Map.of(), source);
    }

    /** @return whether the component starts on first use rather than when the robot opens */
    public boolean startsOnFirstUse() {
        return listen.isEmpty() && connect.isEmpty();
    }
}
