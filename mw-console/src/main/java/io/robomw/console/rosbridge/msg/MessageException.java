package io.robomw.console.rosbridge.msg;

/**
 * A message a client sent does not fit its type: a field the type does not have, a value of the
 * wrong kind, an array of the wrong length. The message says which field, what was expected and
 * what came, in rosbridge_suite's words where it has them.
 */
public final class MessageException extends IllegalArgumentException {

    private static final long serialVersionUID = 1L;

    /** @param message what does not fit */
    public MessageException(String message) {
        super(message);
    }
}
