package io.robomw.api;

import java.util.List;
import java.util.Map;

/**
 * {@link Agency#dispatchClones} could send clones to some of the hosts but not to others. The
 * clones that went are travelling: {@link #sent()} holds their handles, so the caller can still
 * wait for their results (nothing is abandoned); {@link #unsent()} says, per host, why its clone
 * could not be sent.
 */
public class PartialDispatchException extends AgentException {

    private static final long serialVersionUID = 1L;

    private final transient List<AgentRef> sent;
    private final Map<String, String> unsent;

    /**
     * @param message what happened, naming the hosts
     * @param sent    the handles of the clones that were sent, in the order of their hosts
     * @param unsent  each host whose clone could not be sent, and why, in the order given
     */
    public PartialDispatchException(String message, List<AgentRef> sent, Map<String, String> unsent) {
        super(message);
        this.sent = List.copyOf(sent);
        this.unsent = java.util.Collections.unmodifiableMap(new java.util.LinkedHashMap<>(unsent));
    }

    /** @return the handles of the clones that were sent and travel now */
    public List<AgentRef> sent() {
        return sent == null ? List.of() : sent;
    }

    /** @return each host whose clone could not be sent, and why */
    public Map<String, String> unsent() {
        return unsent;
    }
}
