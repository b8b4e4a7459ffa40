package io.robomw.api;

/** Something a robot was asked to do failed. Subclasses say why. */
public class RobotException extends RuntimeException {

    private static final long serialVersionUID = 1L;

    /**
     * @param message what failed, on which robot, and what to do
     */
    public RobotException(String message) {
        super(message);
    }

    /**
     * @param message what failed
     * @param cause   the cause
     */
    public RobotException(String message, Throwable cause) {
        super(message, cause);
    }
}
