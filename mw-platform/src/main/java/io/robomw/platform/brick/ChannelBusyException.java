package io.robomw.platform.brick;

import io.robomw.platform.link.LinkTimeoutException;

import java.time.Duration;

/**
 * An exchange could not have the channel: the one under way (another thread's: a sensor read, the
 * link agent's service) held it past the waiter's deadline, the reply timeout plus the time that
 * exchange was expected to take. The link itself is not known to have failed: the exchange under
 * way ends by its own timeouts, and reports a failure if there is one.
 */
public final class ChannelBusyException extends LinkTimeoutException {

    private static final long serialVersionUID = 1L;

    /**
     * @param robot  the robot's name
     * @param link   the link, as {@code Link.describe()} gives it
     * @param waited how long the exchange waited for the channel
     */
    public ChannelBusyException(String robot, String link, Duration waited) {
        super(link, "robot '" + robot + "': the exchange under way on the channel did not end", waited);
    }
}
