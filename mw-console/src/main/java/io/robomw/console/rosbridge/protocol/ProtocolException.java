package io.robomw.console.rosbridge.protocol;

/**
 * A client's request cannot be carried out: the message says why, in words a client's user can
 * act on. The connection goes on.
 */
final class ProtocolException extends RuntimeException {

    private static final long serialVersionUID = 1L;

    ProtocolException(String message) {
        super(message);
    }

    ProtocolException(String message, Throwable cause) {
        super(message, cause);
    }
}
