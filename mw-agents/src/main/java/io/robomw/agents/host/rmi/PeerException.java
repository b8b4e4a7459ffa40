package io.robomw.agents.host.rmi;

import java.io.IOException;

/**
 * A call to another host failed. {@link #delivered()} says whether the request may have reached
 * it: a refused connection certainly did not, a connection lost mid-call may have, and an agent
 * sent in such a call must not be sent anywhere else, or there could be two of it.
 */
public final class PeerException extends IOException {

    private static final long serialVersionUID = 1L;
    private final boolean delivered;

    public PeerException(String message, boolean delivered, Throwable cause) {
        super(message, cause);
        this.delivered = delivered;
    }

    /** @return whether the host may have received the request */
    public boolean delivered() {
        return delivered;
    }
}
