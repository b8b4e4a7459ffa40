package io.robomw.agents.host.protocol;

import io.robomw.agents.host.HostDescription;
import io.robomw.agents.host.OwedDelivery;
import io.robomw.agents.host.OwedSelector;
import io.robomw.agents.host.ops.HostWatch;
import io.robomw.agents.host.rmi.AgentHostRemote;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

/**
 * The operations of {@link AgentHostRemote#call}. Each travels as its {@link #code()} in the
 * request's operation byte (the table is in {@link Session}), never as its position here.
 */
public enum Op implements WireCode {
    /** An agent hops to this host. */
    TRANSFER(0),
    /** The code archive a transfer needs. */
    PUT_ARCHIVE(1),
    /** List the agents here. */
    LIST(2),
    /** Something for an agent's home: arrival, report, result, end. */
    EVENT(3),
    /** A message for an agent here. */
    MESSAGE(4),
    /** Send an agent here home. */
    RETRACT(5),
    /** End an agent's trip here. */
    DISPOSE(6),
    /** Say who this host is: name, robot, messaging addresses, the hosts it knows ({@link HostDescription}). */
    DESCRIBE(7),
    /** What a watcher (a console) sees: the host, its agents and itineraries, recent events ({@link HostWatch}). */
    WATCH(8),
    /** List the reports and results this host owes homes and has not delivered ({@link OwedDelivery}). */
    OWED(9),
    /** Drop owed deliveries ({@link OwedSelector}); the reply lists the ones dropped. */
    DROP_OWED(10),
    /**
     * News for a home that several of its agents arrived elsewhere, in one call ({@code Bodies.arrivals});
     * sent on the agent wire when the host offers one. A host of a build before it refuses the code, and
     * is then sent one {@link #EVENT} per arrival.
     */
    ARRIVALS(11);

    private static final WireCodes<Op> CODES = WireCodes.of(Op.class, "operation");

    private final int code;

    Op(int code) {
        this.code = code;
    }

    /** @return the operation's code on the wire */
    @Override
    public int code() {
        return code;
    }

    /**
     * @param code an operation byte as received (unsigned)
     * @return its operation
     * @throws IllegalArgumentException naming the code if no operation has it
     */
    public static Op fromCode(int code) {
        return CODES.get(code);
    }
}
