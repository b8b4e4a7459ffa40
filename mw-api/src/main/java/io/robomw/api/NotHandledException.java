package io.robomw.api;

/** An agent's {@link Agent#handleMessage} returned {@code false} for a message sent to it. */
public class NotHandledException extends AgentException {

    private static final long serialVersionUID = 1L;

    /** @param message which agent did not handle what */
    public NotHandledException(String message) {
        super(message);
    }
}
