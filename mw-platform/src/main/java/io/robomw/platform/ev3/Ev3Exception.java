package io.robomw.platform.ev3;

import io.robomw.api.RobotException;

/**
 * The EV3 answered a direct command with {@code DIRECT_REPLY_ERROR}: the firmware found the header
 * malformed, or the virtual machine failed while running the byte codes (an unknown opcode, a bad
 * port or parameter). The reply does not say which instruction failed, so the message names every
 * instruction of the command, with its port, and the message counter.
 */
public class Ev3Exception extends RobotException {

    private static final long serialVersionUID = 1L;

    private final int counter;

    /**
     * @param robot   the robot
     * @param command the command the brick refused
     * @param counter its message counter
     */
    public Ev3Exception(String robot, Ev3Command command, int counter) {
        super(String.format("robot '%s': the EV3 answered DIRECT_REPLY_ERROR to direct command #%d (%s): "
                        + "the firmware refused its header or failed running it (an unknown opcode, a bad port or a bad parameter)",
                robot, counter, command.describe()));
        this.counter = counter;
    }

    /** @return the message counter of the refused command */
    public int counter() {
        return counter;
    }
}
