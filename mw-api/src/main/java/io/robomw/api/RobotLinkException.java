package io.robomw.api;

/** The link to a robot's hardware failed: the brick stopped answering, or its port closed. */
public class RobotLinkException extends RobotException {

    private static final long serialVersionUID = 1L;

    /**
     * @param message which robot, which link, and what happened
     * @param cause   the I/O failure, or {@code null}
     */
    public RobotLinkException(String message, Throwable cause) {
        super(message, cause);
    }
}
