package io.robomw.console.mcap;

import java.io.IOException;

/**
 * Bytes that are not a well-formed MCAP file: the message names the file (or source), the byte
 * offset, the record and what is wrong with it.
 */
public final class McapFormatException extends IOException {

    private static final long serialVersionUID = 1L;

    /** @param message what is wrong, and where */
    public McapFormatException(String message) {
        super(message);
    }

    /** @param message what is wrong, and where @param cause the underlying failure */
    public McapFormatException(String message, Throwable cause) {
        super(message, cause);
    }
}
