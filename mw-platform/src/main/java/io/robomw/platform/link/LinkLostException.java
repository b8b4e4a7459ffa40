package io.robomw.platform.link;

import java.io.IOException;

/**
 * The peer of a {@link Link} is gone: the brick hung up, the serial port vanished (a pseudo-terminal
 * master closed, a USB adapter was unplugged) or the TCP peer closed or reset the connection.
 *
 * <p>The link stays open but every transfer on it fails until it is closed and opened again
 * ({@link Communicator#reopen()}). A {@link TcpServerLink} is the exception: its next read accepts
 * the next peer.
 */
public class LinkLostException extends IOException {

    private static final long serialVersionUID = 1L;

    private final String link;

    /**
     * @param link         the link, as {@link Link#describe()} gives it
     * @param whatHappened what was seen, e.g. {@code "read failed: the port hung up (errno 5)"}
     */
    public LinkLostException(String link, String whatHappened) {
        this(link, whatHappened, null);
    }

    /**
     * @param link         the link, as {@link Link#describe()} gives it
     * @param whatHappened what was seen
     * @param cause        the underlying failure, or {@code null}
     */
    public LinkLostException(String link, String whatHappened, Throwable cause) {
        super(link + ": link lost: " + whatHappened, cause);
        this.link = link;
    }

    /** @return the link that was lost, as {@link Link#describe()} gave it */
    public String link() {
        return link;
    }
}
