package io.robomw.agents.messaging.security;

/** A payload could not be deserialized: its class is not on the allow-list, or it broke a limit. */
public final class PayloadRejectedException extends Exception {

    private static final long serialVersionUID = 1L;

    /**
     * @param message which class or limit
     * @param cause   the deserialization failure
     */
    public PayloadRejectedException(String message, Throwable cause) {
        super(message, cause);
    }
}
