package io.robomw.agents.host.code;

/** Agent state (or a value it carries) was refused: the message says which rule it broke. */
public final class StateRejectedException extends Exception {

    private static final long serialVersionUID = 1L;

    /** @param message which rule the state broke */
    public StateRejectedException(String message) {
        super(message);
    }

    /**
     * @param message which rule the state broke
     * @param cause   the exception reading it raised
     */
    public StateRejectedException(String message, Throwable cause) {
        super(message, cause);
    }
}
