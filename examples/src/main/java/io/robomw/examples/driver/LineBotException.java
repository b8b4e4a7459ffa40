package io.robomw.examples.driver;

import io.robomw.api.RobotException;

/**
 * The LineBot answered a request with {@code ERR}: it refused it. The link is fine; the command
 * that sent the request fails with this.
 */
public final class LineBotException extends RobotException {

    private static final long serialVersionUID = 1L;

    /**
     * @param robot   the robot's name
     * @param request the request it refused
     * @param refusal what it answered
     */
    public LineBotException(String robot, String request, LineBotProtocol.Refusal refusal) {
        super("robot '" + robot + "': the LineBot refused '" + request + "': error " + refusal.error().code() + " ("
                + refusal.error().name().toLowerCase(java.util.Locale.ROOT).replace('_', ' ') + "): " + refusal.text());
    }
}
