package io.robomw.agents.messaging;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentSkipListSet;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.Supplier;

/**
 * What a node announces about itself ({@link PresenceRecord}): the transports that can announce
 * (an MQTT broker, which keeps it retained) do so when they connect, whenever it changes, and
 * when the node closes. The agent host a node belongs to sets itself here; a
 * {@link io.robomw.agents.messaging.robot.RobotServer} adds its robot. Thread-safe.
 */
public final class Presence {

    private final String node;
    private final Supplier<List<Address>> addresses;
    private final Set<String> robots = new ConcurrentSkipListSet<>();
    private final List<Runnable> listeners = new CopyOnWriteArrayList<>();
    private volatile String host;
    private volatile String hostAddress;
    private volatile List<String> agents = List.of();
    private volatile io.robomw.agents.messaging.security.PresenceSeal seal;

    Presence(String node, Supplier<List<Address>> addresses) {
        this.node = node;
        this.addresses = addresses;
    }

    /**
     * @param name    the agent host's name
     * @param address its address ({@code rmi://host:port/name})
     */
    public void host(String name, String address) {
        this.host = name;
        this.hostAddress = address;
        changed();
    }

    /** @param name a robot the node now serves */
    public void addRobot(String name) {
        if (robots.add(name)) {
            changed();
        }
    }

    /** @param name a robot the node no longer serves */
    public void removeRobot(String name) {
        if (robots.remove(name)) {
            changed();
        }
    }

    /** @param descriptions the agents on the node's host, each "ID CLASS STATUS" */
    public void agents(List<String> descriptions) {
        List<String> copy = List.copyOf(descriptions);
        if (!copy.equals(agents)) {
            agents = copy;
            changed();
        }
    }

    /**
     * @param client               the MQTT client identifier it is announced with
     * @param sessionExpirySeconds how long the broker keeps its session while it is away
     * @param via                  the address it is announced through (listed first)
     * @param since                when its connection there began (the time of its will)
     * @return the node as it is now, online
     */
    public PresenceRecord now(String client, long sessionExpirySeconds, String via, Instant since) {
        List<String> messaging = new ArrayList<>();
        messaging.add(via);
        for (Address a : addresses.get()) {
            String s = a.toString();
            if (!messaging.contains(s)) {
                messaging.add(s);
            }
        }
        String h = host;
        String ha = hostAddress;
        return new PresenceRecord(node, true, Instant.now(), since, client, sessionExpirySeconds, messaging, ha == null ? null : h, ha, List.copyOf(robots), agents);
    }

    /**
     * Signs what the node announces from now on (an agent host gives its node the seal of its cluster key).
     *
     * @param seal the cluster's seal
     */
    public void seal(io.robomw.agents.messaging.security.PresenceSeal seal) {
        this.seal = seal;
        changed();
    }

    /**
     * @param record a record of this node
     * @return its stored form, signed when the node has a seal
     */
    public byte[] encode(PresenceRecord record) {
        return record.encode(seal);
    }

    /** @param listener told (on the changing thread) whenever what is announced changes */
    public void onChange(Runnable listener) {
        listeners.add(listener);
    }

    /** @param listener no longer told */
    public void removeListener(Runnable listener) {
        listeners.remove(listener);
    }

    private void changed() {
        listeners.forEach(Runnable::run);
    }
}
