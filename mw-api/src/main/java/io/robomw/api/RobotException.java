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

    /**
     * For exceptions raised by the middleware's own threads, whose stack trace would only show
     * that thread's loop: created without one, which keeps them cheap.
     *
     * @param message what failed
     * @param cause   the cause, or {@code null}
     * @param withStackTrace whether to record a stack trace
     */
    protected RobotException(String message, Throwable cause, boolean withStackTrace) {
        super(message, cause, true, withStackTrace);
    }
}
