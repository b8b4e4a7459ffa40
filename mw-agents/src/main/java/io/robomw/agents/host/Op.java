package io.robomw.agents.host;

/**
 * The operations of {@link AgentHostRemote#call}. Each travels as its {@link #code()} in the
 * request's operation byte (the table is in {@link Session}), never as its position here.
 */
enum Op {
    /** An agent hops to this host. Code 0. */
    TRANSFER(0),
    /** The code archive a transfer needs. Code 1. */
    PUT_ARCHIVE(1),
    /** List the agents here. Code 2. */
    LIST(2),
    /** Something for an agent's home: arrival, report, result, end. Code 3. */
    EVENT(3),
    /** A message for an agent here. Code 4. */
    MESSAGE(4),
    /** Send an agent here home. Code 5. */
    RETRACT(5),
    /** End an agent's trip here. Code 6. */
    DISPOSE(6),
    /** Say who this host is: name, robot, messaging addresses, the hosts it knows ({@link HostDescription}). Code 7. */
    DESCRIBE(7),
    /** What a watcher (a console) sees: the host, its agents and itineraries, recent events ({@link HostWatch}). Code 8. */
    WATCH(8),
    /** List the reports and results this host owes homes and has not delivered ({@link OwedDelivery}). Code 9. */
    OWED(9),
    /** Drop owed deliveries ({@link OwedSelector}); the reply lists the ones dropped. Code 10. */
    DROP_OWED(10);

    private final int code;

    Op(int code) {
        this.code = code;
    }

    /** @return the operation's code on the wire */
    int code() {
        return code;
    }

    /**
     * @param code an operation byte as received (unsigned)
     * @return its operation
     * @throws IllegalArgumentException naming the code if no operation has it
     */
    static Op fromCode(int code) {
        return switch (code) {
            case 0 -> TRANSFER;
            case 1 -> PUT_ARCHIVE;
            case 2 -> LIST;
            case 3 -> EVENT;
            case 4 -> MESSAGE;
            case 5 -> RETRACT;
            case 6 -> DISPOSE;
            case 7 -> DESCRIBE;
            case 8 -> WATCH;
            case 9 -> OWED;
            case 10 -> DROP_OWED;
            default -> throw new IllegalArgumentException("unknown operation code " + code
                    + " (this host knows 0-10: TRANSFER, PUT_ARCHIVE, LIST, EVENT, MESSAGE, RETRACT, DISPOSE, DESCRIBE, WATCH, OWED, DROP_OWED)");
        };
    }
}
