package io.robomw.platform.link;

import java.io.IOException;

/**
 * Told when a {@link Communicator}'s link drops and when it works again. Each drop is reported
 * once, however many sends and receives fail afterwards, and each restore once.
 *
 * <p>Callbacks run on the thread whose send, receive or reopen saw the change, so they must be
 * quick and must not call back into the communicator's I/O. An exception thrown by a listener is
 * logged and ignored.
 */
public interface LinkListener {

    /**
     * The link was lost.
     *
     * @param link  the link, as {@link Link#describe()} gives it
     * @param cause what the link reported, usually a {@link LinkLostException}
     */
    default void onLinkLost(String link, IOException cause) {
    }

    /**
     * The link works again after a loss: a reopen succeeded, or bytes moved again (a
     * {@link TcpServerLink} accepted the next peer).
     *
     * @param link the link, as {@link Link#describe()} gives it
     */
    default void onLinkRestored(String link) {
    }
}
