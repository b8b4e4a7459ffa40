package io.robomw.console.observe;

import java.util.List;

/**
 * An agent host as the console last saw it.
 *
 * @param address   {@code rmi://host:port/name}
 * @param name      its name
 * @param up        whether it answered the last time it was asked
 * @param robot     the robot its agents drive, "" for none, {@code null} if the host does not say
 * @param agents    the agents there (as last seen, when it is down)
 * @param owed      deliveries the host owes to agents' homes, or {@code null} when the host does not
 *                  report them (hosts report them from the agents' delivery issue on; the console
 *                  shows them when they do)
 * @param error     why it did not answer, or ""
 * @param lastContactNanos when it last answered, ns since the epoch (0 = never)
 */
public record HostView(String address, String name, boolean up, String robot, List<AgentView> agents, List<OwedDelivery> owed, String error,
                       long lastContactNanos) {

    /** Copies. */
    public HostView {
        agents = List.copyOf(agents);
        owed = owed == null ? null : List.copyOf(owed);
    }

    /**
     * @param reason       why it did not answer
     * @return this host, down, with what was last seen of it
     */
    public HostView down(String reason) {
        return new HostView(address, name, false, robot, agents, owed, reason, lastContactNanos);
    }

    /**
     * One agent at a host.
     *
     * @param id           its id
     * @param className    its class
     * @param status       ACTIVE, IN_TRANSIT...
     * @param hop          the hop that brought it
     * @param home         where its results go
     * @param itinerary    its stops, past and next, or {@code null} when the host does not say
     * @param currentStop  index of the stop it is at in {@code itinerary}, -1 if unknown
     */
    public record AgentView(String id, String className, String status, long hop, String home, List<StopView> itinerary, int currentStop) {
        /** Copies. */
        public AgentView {
            itinerary = itinerary == null ? null : List.copyOf(itinerary);
        }
    }

    /**
     * A stop of an itinerary.
     *
     * @param host    where
     * @param outcome DONE, FAILED, UNREACHABLE, INTERRUPTED for a visited stop, "" for one still ahead
     * @param detail  what went wrong, or ""
     * @param round   which round of a repeated itinerary, from 0
     */
    public record StopView(String host, String outcome, String detail, int round) {
    }

    /**
     * Events a host still has to deliver to an agent's home.
     *
     * @param home       the home
     * @param count      how many
     * @param oldestNanos when the oldest was made, ns since the epoch
     */
    public record OwedDelivery(String home, int count, long oldestNanos) {
    }
}
