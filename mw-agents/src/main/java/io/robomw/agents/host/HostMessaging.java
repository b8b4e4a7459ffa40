package io.robomw.agents.host;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Itinerary;
import io.robomw.api.Messaging;
import io.robomw.api.UnsupportedActionException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.RejectedExecutionException;

/**
 * A host's messaging: the node its agents use ({@code context().messaging()}, each through its own
 * {@link AgentMessaging}), the directory of other hosts, and the host's description for
 * {@link Op#DESCRIBE}.
 *
 * <p>The host's node is connected to the nodes of the hosts it knows: when it meets a new host
 * (an agent's home or stop), it describes it in the background and connects to its messaging
 * address, so that a publication by an agent anywhere in the cluster reaches the subscribers of
 * every host that knows the publisher's host, and subscriptions travel the same links.
 *
 * <p>Thread-safe.
 */
final class HostMessaging implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(HostMessaging.class);

    private final HostState host;
    private final Peers peers;
    private final MessagingNode node;
    private final boolean ownsNode;
    private final Set<String> met = ConcurrentHashMap.newKeySet();
    private final Set<String> connected = ConcurrentHashMap.newKeySet();
    private volatile HostDirectory directory;
    private final List<AutoCloseable> brokerDirectories = new java.util.concurrent.CopyOnWriteArrayList<>();
    /** Agent hosts announced at a broker the node is at, by agent host address. */
    private final java.util.Map<String, Announced> announced = new ConcurrentHashMap<>();
    private volatile ClusterKey eventsKey;
    private volatile java.util.function.BiFunction<String, byte[], Reply> onEvent;
    private volatile BrokerEvents brokerEvents;

    /** An agent host seen at a broker: where, whether it is up, and whether the broker keeps messages for it while it is away. */
    private record Announced(String broker, boolean online, long sessionExpirySeconds) {
    }

    /**
     * @param host     the host
     * @param peers    how other hosts are called
     * @param node     the host's node, or {@code null} for a host without messaging
     * @param ownsNode whether closing the host closes the node
     */
    HostMessaging(HostState host, Peers peers, MessagingNode node, boolean ownsNode) {
        this.host = host;
        this.peers = peers;
        this.node = node;
        this.ownsNode = ownsNode;
    }

    /** The messaging address as given, with its options (a broker's credentials file), or {@code null}. */
    private volatile String given;

    /** @param address the messaging address the host was given, options and all, or {@code null} */
    void given(String address) {
        this.given = address;
    }

    /** @return the bound broker address with the options it was given (its credentials), if it is the one given */
    private String withOptions(String bound) {
        String g = given;
        try {
            if (g != null && io.robomw.agents.messaging.Address.parse(g).endpoint().equals(io.robomw.agents.messaging.Address.parse(bound).endpoint())) {
                return g;
            }
        } catch (IllegalArgumentException e) {
            // not an address: the bound one
        }
        return bound;
    }

    /**
     * Lets agent events travel through the brokers the node is at ({@link BrokerEvents}).
     *
     * @param key     the cluster key (the events' topic password is derived from it)
     * @param handler what this host does with an event for one of its agents ({@code Home#onEvent})
     */
    void events(ClusterKey key, java.util.function.BiFunction<String, byte[], Reply> handler) {
        this.eventsKey = key;
        this.onEvent = handler;
    }

    /** A broker the host's own node joins once the host knows its address, or {@code null}. */
    private volatile String deferredBroker;

    /**
     * The host's own node joins this broker only in {@link #started()}, once its presence names the
     * host: the presence it leaves there as its will (the offline version, published when the host
     * is gone without closing, as after kill -9) is made when it joins, so it must already name the
     * host, or {@code mw agents --cluster} would not see the host go offline.
     *
     * @param broker an {@code mqtt://} or {@code mqtts://} address
     */
    void joinWhenStarted(String broker) {
        this.deferredBroker = broker;
    }

    /** Called once the host knows its own address, before it takes calls. */
    void started() {
        directory = new HostDirectory(host.address);
        if (node != null && host.robot != null) {
            node.answerTo(host.robot.name());
        }
        if (node != null && eventsKey != null && onEvent != null) {
            brokerEvents = new BrokerEvents(node, eventsKey, host.name);
            brokerEvents.receive(onEvent);
        }
        if (node != null) {
            if (eventsKey != null) {
                // what the node announces at a broker is signed with the cluster key; presences not signed with it are ignored
                node.presence().seal(eventsKey.presenceSeal());
            }
            node.presence().host(host.name, host.address);
            if (deferredBroker != null) {
                node.bind(deferredBroker);
            }
            for (String broker : addresses()) {
                if (broker.startsWith("mqtt://") || broker.startsWith("mqtts://")) {
                    watchBroker(broker, withOptions(broker));
                }
            }
        }
    }

    /**
     * Learns the agent hosts announced at a broker the node is at, as they come and go, so that
     * agents here can address them by name (through the broker: hosts found there may be out of
     * reach otherwise).
     *
     * @param broker      the broker as the node is bound to it (events to hosts announced there go through it)
     * @param withOptions the same with the options it was given (its credentials), to read the presences with
     */
    private void watchBroker(String broker, String withOptions) {
        try {
            io.robomw.agents.messaging.mqtt.BrokerDirectory d = io.robomw.agents.messaging.mqtt.BrokerDirectory.open(withOptions,
                    node.settings().connectTimeout(), node.settings().tls(), eventsKey == null ? null : eventsKey.presenceSeal(),
                    node.replayDirectory().map(dir -> io.robomw.agents.messaging.security.ReplayStore.fileFor(dir, host.name + ".presence")).orElse(null));
            brokerDirectories.add(d);
            d.onPresence(p -> {
                if (p.host() != null && !p.hostAddress().equals(host.address)) {
                    announced.put(p.hostAddress(), new Announced(broker, p.online(), p.sessionExpirySeconds()));
                }
                HostDirectory dir = directory;
                if (dir != null && p.online() && p.host() != null && !p.hostAddress().equals(host.address)) {
                    List<String> viaBroker = p.messaging().stream().filter(m -> m.startsWith("mqtt")).toList();
                    dir.learn(new HostDescription(p.host(), p.hostAddress(), p.robots().isEmpty() ? "" : p.robots().get(0), viaBroker, List.of()));
                }
            });
        } catch (java.io.IOException | RuntimeException e) {
            LOG.warn("host {}: cannot read the hosts announced at {}: {}", host.name, broker, e.getMessage());
        }
    }

    /**
     * @param home an agent's home
     * @return the broker to send the home's events through: one the home is announced at and where
     *         it receives now, or where the broker keeps them for it while it is away; {@code null} for
     *         the home's own address (RMI)
     */
    String brokerFor(String home) {
        Announced a = announced.get(home);
        return a != null && brokerEvents != null && (a.online() || a.sessionExpirySeconds() > 0) ? a.broker() : null;
    }

    /** Delivers one event to a home through a broker ({@link BrokerEvents#deliver}). */
    void deliverThroughBroker(String broker, String home, AgentEvent event) throws java.io.IOException {
        brokerEvents.deliver(broker, home, event);
    }

    /** @return the node, or {@code null} when the host has none */
    MessagingNode node() {
        return node;
    }

    /** @return where the node receives; empty without one */
    List<String> addresses() {
        return node == null ? List.of() : node.boundAddresses().stream().map(Object::toString).toList();
    }

    /**
     * @param nameOrAddress an agent host's name or address
     * @param h             the agent asking (its home is asked about names this host does not know)
     * @return the host's agent host address
     * @throws IllegalArgumentException when no host of that name is known
     */
    String hostAddress(String nameOrAddress, HostedAgent h) {
        if (nameOrAddress.equals(host.name)) {
            return host.address;
        }
        return directory.hostAddress(nameOrAddress, h.home, peers::describe);
    }

    /** @return an agent's view of the node, made on first use and released when the agent leaves */
    Messaging forAgent(HostedAgent h) {
        if (node == null) {
            throw new UnsupportedActionException(host.name, "messaging", "agent host " + host.address
                    + " was started without messaging (mw host --no-messaging); start it with a messaging node (the default)");
        }
        synchronized (h) {
            if (h.messaging == null) {
                h.messaging = new AgentMessaging(node, target -> directory.resolve(target, h.home, peers::describe));
            }
            return h.messaging;
        }
    }

    /** The agent leaves this host or ends: its listeners here are removed. */
    void left(HostedAgent h) {
        AgentMessaging m;
        synchronized (h) {
            m = h.messaging;
            h.messaging = null;
        }
        if (m != null) {
            m.release();
        }
    }

    /** Learns the hosts an agent here knows of: its home and its itinerary's stops. */
    void met(HostedAgent h) {
        met(h.home);
        for (Itinerary.Stop s : h.agent.itinerary().stops()) {
            met(s.host());
        }
    }

    /** Learns of a host met on the way; a new one is described and connected to in the background. */
    void met(String hostAddress) {
        HostDirectory d = directory;
        if (d == null || hostAddress == null || hostAddress.equals(host.address) || !met.add(hostAddress)) {
            return;
        }
        d.learn(hostAddress);
        if (node == null || host.closed) {
            return;
        }
        try {
            host.requests.execute(() -> connect(hostAddress));
        } catch (RejectedExecutionException closing) {
            met.remove(hostAddress);
        }
    }

    private void connect(String hostAddress) {
        try {
            HostDescription other = peers.describe(hostAddress);
            directory.learn(other);
            other.messaging().stream().filter(m -> m.startsWith("tcp://")).findFirst().ifPresent(m -> {
                if (connected.add(m) && !addresses().contains(m)) {
                    node.connect(m);
                    LOG.info("host {}: messaging connected to {} ({})", host.name, other.name(), m);
                }
            });
            other.known().forEach(k -> met(k.address()));
        } catch (PeerException | RuntimeException e) {
            met.remove(hostAddress); // asked again when it is met again
            LOG.debug("host {}: cannot describe {} yet: {}", host.name, hostAddress, e.toString());
        }
    }

    /** @return what this host says of itself when asked */
    HostDescription describeSelf() {
        HostDirectory d = directory;
        return new HostDescription(host.name, host.address, host.robot == null ? "" : host.robot.name(), addresses(),
                d == null ? List.of() : d.known());
    }

    @Override
    public void close() {
        for (AutoCloseable d : brokerDirectories) {
            try {
                d.close();
            } catch (Exception e) {
                LOG.debug("host {}: closing a broker directory: {}", host.name, e.toString());
            }
        }
        if (node != null && ownsNode) {
            node.close();
        }
    }
}
