package io.robomw.platform.mavlink.gcs;

import io.robomw.api.RobotException;
import io.robomw.platform.mavlink.wire.MavResult;

/**
 * A vehicle answered a command with a COMMAND_ACK other than ACCEPTED (or IN_PROGRESS): the
 * result says whether asking again later may work ({@link MavResult#TEMPORARILY_REJECTED}: "retrying
 * later should work", in MAVLink's words) or not.
 */
public final class CommandRefusedException extends RobotException {

    private static final long serialVersionUID = 1L;

    private final transient MavResult result;

    /**
     * @param message what was refused, naming the robot and the command
     * @param result  the vehicle's answer
     */
    public CommandRefusedException(String message, MavResult result) {
        super(message);
        this.result = result;
    }

    /** @return the vehicle's answer */
    public MavResult result() {
        return result;
    }

    /** @return whether the vehicle said to ask again later */
    public boolean temporary() {
        return result == MavResult.TEMPORARILY_REJECTED;
    }
}
