package io.robomw.api;

/** Something asked of a mobile agent or an agent host failed; the message says which agent and host. */
public class AgentException extends RobotException {

    private static final long serialVersionUID = 1L;

    /** @param message what failed, for which agent, at which host */
    public AgentException(String message) {
        super(message);
    }

    /**
     * @param message what failed
     * @param cause   the cause
     */
    public AgentException(String message, Throwable cause) {
        super(message, cause);
    }
}
