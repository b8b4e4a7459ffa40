package io.robomw.agents.host;

import io.robomw.api.UnsupportedActionException;

/** An agent asked for the robot of a host that has none: what {@code context().robot()} throws there. */
public final class NoRobotException extends UnsupportedActionException {

    private static final long serialVersionUID = 1L;

    /**
     * @param hostName    the host
     * @param hostAddress its address
     */
    public NoRobotException(String hostName, String hostAddress) {
        super("agent host " + hostName + " (" + hostAddress + ") has no robot: start it with mw host --robot FILE, or --world FILE --world-robot NAME",
                null, "none at host " + hostName, "robot()");
    }
}
