package io.robomw.agents.host.protocol;

import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

import java.nio.charset.StandardCharsets;

/**
 * A host's answer to one call.
 *
 * @param status what happened
 * @param body   the answer's data (a reason for refusals)
 */
public record Reply(Status status, byte[] body) {

    /**
     * Outcomes of a call. Each travels as its {@link #code()} in the reply's status byte (the table
     * is in {@link Session}), never as its position here.
     */
    public enum Status implements WireCode {
        /** Done. */
        OK(0),
        /** The transfer names an archive this host lacks: send it, then the transfer again. */
        NEED_ARCHIVE(1),
        /** Already done before (a retried transfer); counts as done. */
        DUPLICATE(2),
        /** Refused; the body says why. */
        REFUSED(3),
        /** The agent has moved on; the body is where to. */
        MOVED(4),
        /** No such agent here. */
        GONE(5),
        /** The agent did not handle the message. */
        NOT_HANDLED(6),
        /** The session is unknown (the host restarted): authenticate again. Sent alone and without a MAC. */
        UNKNOWN_SESSION(7);

        private static final WireCodes<Status> CODES = WireCodes.of(Status.class, "reply status");

        private final int code;

        Status(int code) {
            this.code = code;
        }

        /** @return the status's code on the wire */
        @Override
        public int code() {
            return code;
        }

        /**
         * @param code a status byte as received (unsigned)
         * @return its status
         * @throws IllegalArgumentException naming the code if no status has it
         */
        public static Status fromCode(int code) {
            return CODES.get(code);
        }
    }

    public static Reply ok() {
        return new Reply(Status.OK, new byte[0]);
    }

    public static Reply ok(byte[] body) {
        return new Reply(Status.OK, body);
    }

    public static Reply of(Status status, String text) {
        return new Reply(status, text.getBytes(StandardCharsets.UTF_8));
    }

    public String text() {
        return new String(body, StandardCharsets.UTF_8);
    }
}
