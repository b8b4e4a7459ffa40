package io.robomw.platform.nxt;

import io.robomw.api.RobotException;

/** The NXT answered a command with a status other than success. */
public class NxtException extends RobotException {

    private static final long serialVersionUID = 1L;

    private final int status;

    /**
     * @param robot   the robot
     * @param opcode  the command's opcode
     * @param port    the port it was for, or -1
     * @param status  the status byte
     */
    public NxtException(String robot, int opcode, int port, int status) {
        this(robot, opcode, port, status, null);
    }

    /**
     * @param robot    the robot
     * @param opcode   the command's opcode
     * @param port     the port it was for, or -1
     * @param status   the status byte
     * @param telegram the telegram the brick refused, for the message, or {@code null}
     */
    public NxtException(String robot, int opcode, int port, int status, byte[] telegram) {
        super(String.format("robot '%s': NXT refused %s%s: status 0x%02X, %s%s", robot, NxtTelegram.name(opcode),
                port < 0 ? "" : " on port " + port, status, NxtStatus.describe(status),
                telegram == null ? "" : " (telegram " + java.util.HexFormat.ofDelimiter(" ").withUpperCase().formatHex(telegram) + ")"));
        this.status = status;
    }

    /** @return the status byte */
    public int status() {
        return status;
    }
}
