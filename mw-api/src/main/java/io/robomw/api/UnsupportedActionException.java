package io.robomw.api;

/**
 * The robot cannot do what it was asked: flying on a ground robot, a sensor it does not have, a
 * speed above its maximum. Raised before anything moves.
 */
public class UnsupportedActionException extends RobotException {

    private static final long serialVersionUID = 1L;

    private final String robot;
    private final String action;

    /**
     * @param robot  the robot's name
     * @param action the action asked for, for example {@code move(1.0, 9.0)}
     * @param reason why it cannot, with the limit that was broken
     */
    public UnsupportedActionException(String robot, String action, String reason) {
        super("robot '" + robot + "' cannot " + action + ": " + reason);
        this.robot = robot;
        this.action = action;
    }

    /**
     * For subclasses whose message is better said otherwise (a host without any robot).
     *
     * @param message the whole message
     * @param cause   the cause, or {@code null}
     * @param robot   the robot's name, or what stands for it
     * @param action  the action asked for
     */
    protected UnsupportedActionException(String message, Throwable cause, String robot, String action) {
        super(message, cause);
        this.robot = robot;
        this.action = action;
    }

        /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the action that was refused */
    public String action() {
        return action;
    }
}
