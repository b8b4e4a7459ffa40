package io.robomw.api;

/**
 * A message could not be sent or received: the host could not be reached, no reply came in time,
 * the payload is too large, or a password did not match the topic's. The message says which
 * host, topic and limit.
 */
public class MessagingException extends RobotException {

    private static final long serialVersionUID = 1L;

    /**
     * @param message what failed, with the host or topic, and what to do
     */
    public MessagingException(String message) {
        super(message);
    }

    /**
     * @param message what failed
     * @param cause   the cause
     */
    public MessagingException(String message, Throwable cause) {
        super(message, cause);
    }
}
