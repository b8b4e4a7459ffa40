package io.robomw.agents.host;

import java.nio.charset.StandardCharsets;

/**
 * A host's answer to one call.
 *
 * @param status what happened
 * @param body   the answer's data (a reason for refusals)
 */
record Reply(Status status, byte[] body) {

    /** Outcomes of a call. */
    enum Status {
        /** Done. */
        OK,
        /** The transfer names an archive this host lacks: send it, then the transfer again. */
        NEED_ARCHIVE,
        /** Already done before (a retried transfer); counts as done. */
        DUPLICATE,
        /** Refused; the body says why. */
        REFUSED,
        /** The agent has moved on; the body is where to. */
        MOVED,
        /** No such agent here. */
        GONE,
        /** The agent did not handle the message. */
        NOT_HANDLED,
        /** The session is unknown (the host restarted): authenticate again. */
        UNKNOWN_SESSION;

        private static final Status[] ALL = values();

        static Status of(int code) {
            if (code < 0 || code >= ALL.length) {
                throw new IllegalArgumentException("unknown reply status " + code);
            }
            return ALL[code];
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
