package io.robomw.api;

/**
 * A command was interrupted before it finished, because a newer command took the same actuators
 * (most recent wins), or a safety stop did. Raised by the execution action thread, so it carries
 * no stack trace; the blocking verbs re-throw it on the caller's thread.
 */
public class CommandPreemptedException extends RobotException {

    private static final long serialVersionUID = 1L;

    /**
     * @param command the interrupted command
     * @param by      the command that took its actuators
     */
    public CommandPreemptedException(String command, String by) {
        super(null, null, false);
        this.command = command;
        this.by = by;
        this.refused = false;
    }

    private CommandPreemptedException(String command, String holder, boolean refused) {
        super(null, null, false);
        this.command = command;
        this.by = holder;
        this.refused = refused;
    }

    private final String command;
    private final String by;
    private final boolean refused;

    /** Built when asked for: most pre-emptions (a refreshed continuous command) are never read. */
    @Override
    public String getMessage() {
        return refused
                ? "command '" + command + "' was refused: its actuators are held by '" + by + "', which a command of its priority may not interrupt"
                : "command '" + command + "' was interrupted by '" + by + "', which needs the same actuators";
    }

    /**
     * @param command the refused command
     * @param holder  the command that holds its actuators and may not be interrupted
     * @return the exception for a command that was refused because its actuators are held
     */
    public static CommandPreemptedException refused(String command, String holder) {
        return new CommandPreemptedException(command, holder, true);
    }
}
