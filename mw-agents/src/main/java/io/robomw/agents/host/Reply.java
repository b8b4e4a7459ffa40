package io.robomw.agents.host;

import java.nio.charset.StandardCharsets;

/**
 * A host's answer to one call.
 *
 * @param status what happened
 * @param body   the answer's data (a reason for refusals)
 */
record Reply(Status status, byte[] body) {

    /**
     * Outcomes of a call. Each travels as its {@link #code()} in the reply's status byte (the table
     * is in {@link Session}), never as its position here.
     */
    enum Status {
        /** Done. Code 0. */
        OK(0),
        /** The transfer names an archive this host lacks: send it, then the transfer again. Code 1. */
        NEED_ARCHIVE(1),
        /** Already done before (a retried transfer); counts as done. Code 2. */
        DUPLICATE(2),
        /** Refused; the body says why. Code 3. */
        REFUSED(3),
        /** The agent has moved on; the body is where to. Code 4. */
        MOVED(4),
        /** No such agent here. Code 5. */
        GONE(5),
        /** The agent did not handle the message. Code 6. */
        NOT_HANDLED(6),
        /** The session is unknown (the host restarted): authenticate again. Code 7, sent alone and without a MAC. */
        UNKNOWN_SESSION(7);

        private final int code;

        Status(int code) {
            this.code = code;
        }

        /** @return the status's code on the wire */
        int code() {
            return code;
        }

        /**
         * @param code a status byte as received (unsigned)
         * @return its status
         * @throws IllegalArgumentException naming the code if no status has it
         */
        static Status fromCode(int code) {
            return switch (code) {
                case 0 -> OK;
                case 1 -> NEED_ARCHIVE;
                case 2 -> DUPLICATE;
                case 3 -> REFUSED;
                case 4 -> MOVED;
                case 5 -> GONE;
                case 6 -> NOT_HANDLED;
                case 7 -> UNKNOWN_SESSION;
                default -> throw new IllegalArgumentException("unknown reply status code " + code + " (known: 0-7)");
            };
        }
    }

    static Reply ok() {
        return new Reply(Status.OK, new byte[0]);
    }

    static Reply ok(byte[] body) {
        return new Reply(Status.OK, body);
    }

    static Reply of(Status status, String text) {
        return new Reply(status, text.getBytes(StandardCharsets.UTF_8));
    }

    String text() {
        return new String(body, StandardCharsets.UTF_8);
    }
}
