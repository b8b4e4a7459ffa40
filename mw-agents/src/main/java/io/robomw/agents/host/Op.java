package io.robomw.agents.host;

/** The operations of {@link AgentHostRemote#call}. */
enum Op {
    /** An agent hops to this host. */
    TRANSFER,
    /** The code archive a transfer needs. */
    PUT_ARCHIVE,
    /** List the agents here. */
    LIST,
    /** Something for an agent's home: arrival, report, result, end. */
    EVENT,
    /** A message for an agent here. */
    MESSAGE,
    /** Send an agent here home. */
    RETRACT,
    /** End an agent's trip here. */
    DISPOSE,
    /** What a watcher (a console) sees: the host, its agents and itineraries, recent events ({@link HostWatch}). */
    WATCH;

    private static final Op[] ALL = values();

    static Op of(int code) {
        if (code < 0 || code >= ALL.length) {
            throw new IllegalArgumentException("unknown operation " + code);
        }
        return ALL[code];
    }
}
