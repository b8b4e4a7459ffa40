package io.robomw.platform.nxt;

/** The NXT firmware's status bytes ({@code c_cmd.h}), with their meanings. */
public final class NxtStatus {

    /** Success. */
    public static final int SUCCESS = 0x00;
    /** An I²C transaction is still under way. */
    public static final int PENDING = 0x20;
    /** Mailbox empty. */
    public static final int MAILBOX_EMPTY = 0x40;
    /** Unknown opcode. */
    public static final int UNKNOWN_COMMAND = 0xBE;
    /** Malformed telegram. */
    public static final int INSANE_PACKET = 0xBF;
    /** A value (a port) out of range. */
    public static final int OUT_OF_RANGE = 0xC0;
    /** I²C bus error. */
    public static final int BUS_ERROR = 0xDD;
    /** Channel not configured or busy. */
    public static final int CHANNEL_NOT_READY = 0xE0;
    /** No program is running. */
    public static final int NO_ACTIVE_PROGRAM = 0xEC;

    private NxtStatus() {
    }

    /**
     * @param status a status byte
     * @return what it means
     */
    public static String describe(int status) {
        return switch (status) {
            case SUCCESS -> "success";
            case PENDING -> "pending communication transaction in progress";
            case MAILBOX_EMPTY -> "specified mailbox queue is empty";
            case 0xBD -> "request failed (file not found?)";
            case UNKNOWN_COMMAND -> "unknown command opcode";
            case INSANE_PACKET -> "insane packet";
            case OUT_OF_RANGE -> "data contains out-of-range values (a bad port?)";
            case BUS_ERROR -> "communication bus error";
            case 0xDE -> "no free memory in communication buffer";
            case 0xDF -> "specified channel/connection is not valid";
            case CHANNEL_NOT_READY -> "specified channel/connection not configured or busy";
            case NO_ACTIVE_PROGRAM -> "no active program";
            case 0xED -> "illegal size specified";
            case 0xEE -> "illegal mailbox queue ID specified";
            case 0xEF -> "attempted to access invalid field of a structure";
            case 0xF0 -> "bad input or output specified";
            case 0xFB -> "insufficient memory available";
            case 0xFF -> "bad arguments";
            default -> String.format("status 0x%02X", status);
        };
    }
}
