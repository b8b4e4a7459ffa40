package io.robomw.agents.messaging.frame;

import io.robomw.agents.messaging.DropReason;

/** An incoming frame cannot be used; {@link #reason()} says why, for the drop counters. */
public final class FrameException extends Exception {

    private static final long serialVersionUID = 1L;

    private final transient DropReason reason;

    /**
     * @param reason  the drop reason
     * @param message what is wrong, with the offending value
     */
    public FrameException(DropReason reason, String message) {
        super(message);
        this.reason = reason;
    }

    /** @return why the frame is dropped */
    public DropReason reason() {
        return reason;
    }
}
