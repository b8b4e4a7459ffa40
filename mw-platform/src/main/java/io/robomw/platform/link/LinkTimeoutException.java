package io.robomw.platform.link;

import java.io.IOException;
import java.time.Duration;

/**
 * Bytes that were expected did not arrive in time. The link itself is still up: this is the brick
 * being slow or silent, not the port going away (that is {@link LinkLostException}).
 */
public class LinkTimeoutException extends IOException {

    private static final long serialVersionUID = 1L;

    private final String link;
    private final Duration timeout;

    /**
     * @param link         the link, as {@link Link#describe()} gives it
     * @param whatHappened what did not arrive, e.g. {@code "received 3 of 7 bytes"}
     * @param timeout      how long was waited
     */
    public LinkTimeoutException(String link, String whatHappened, Duration timeout) {
        super(link + ": " + whatHappened + " within the timeout of " + Deadline.format(timeout));
        this.link = link;
        this.timeout = timeout;
    }

    /** @return the link that timed out, as {@link Link#describe()} gave it */
    public String link() {
        return link;
    }

    /** @return how long was waited */
    public Duration timeout() {
        return timeout;
    }
}
