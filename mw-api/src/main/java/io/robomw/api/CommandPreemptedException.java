package io.robomw.api;

/**
 * A command was interrupted before it finished, because a newer command took the same actuators
 * (most recent wins), or a safety stop did.
 */
public class CommandPreemptedException extends RobotException {

    private static final long serialVersionUID = 1L;

    /**
     * @param command the interrupted command
     * @param by      the command that took its actuators
     */
    public CommandPreemptedException(String command, String by) {
        super("command '" + command + "' was interrupted by '" + by + "', which needs the same actuators");
    }
}
