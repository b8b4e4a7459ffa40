package io.robomw.agents.host;

import io.robomw.api.UnsupportedActionException;

/** An agent asked for the robot of a host that has none. */
final class NoRobotException extends UnsupportedActionException {

    private static final long serialVersionUID = 1L;

    NoRobotException(String hostName, String hostAddress) {
        super("agent host " + hostName + " (" + hostAddress + ") has no robot: start it with mw host --robot FILE, or --world FILE --world-robot NAME",
                null, "none at host " + hostName, "robot()");
    }
}
