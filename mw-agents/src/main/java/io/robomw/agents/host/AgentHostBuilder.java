package io.robomw.agents.host;

import io.robomw.agents.host.messaging.HostMessaging;
import io.robomw.agents.host.visit.SpinHandoff;
import io.robomw.agents.host.wire.WireServer;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.MessagingException;
import io.robomw.api.Robot;
import io.robomw.api.spi.FailurePolicy;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Objects;

/** Settings of an agent host, and its start: {@link AgentHost#builder(String)}. */
public final class AgentHostBuilder {

    final String name;
    String bind = "127.0.0.1";
    int port;
    Robot robot;
    String messagingAddress;
    MessagingSettings messagingSettings = MessagingSettings.defaults();
    boolean withMessaging = true;
    MessagingNode node;
    boolean ownsNode;
    ClusterKey key;
    TlsSettings tls;
    Path storeDir;
    List<String> allowed = List.of();
    long maxStateBytes = 64L << 20;
    Duration callTimeout = Duration.ofSeconds(30);
    Duration stopGrace = Duration.ofSeconds(5);
    Duration runnerSpin = SpinHandoff.defaultSpin();
    Duration endpointSpin = Duration.ZERO;
    DeliveryPolicy delivery = DeliveryPolicy.defaults();
    boolean wire = true;
    int wirePort;
    Duration wireSpin = SpinHandoff.defaultWireSpin();
    Duration wireReadSpin = Duration.ZERO;
    boolean version2Only;
    boolean olderHosts;
    boolean beforeCompactForm;
    WireServer.Limits wireLimits;
    java.util.concurrent.ThreadFactory wireThreads;
    FailurePolicy failures = FailurePolicy.logging();

    AgentHostBuilder(String name) {
        if (name == null || !name.matches("[A-Za-z0-9._-]+")) {
            throw new IllegalArgumentException("'" + name + "' is not a host name: use letters, digits, '.', '_' and '-'");
        }
        this.name = name;
    }

    /** @param address the address to listen on and to be known by (default 127.0.0.1) @return this */
    public AgentHostBuilder bind(String address) {
        this.bind = Objects.requireNonNull(address);
        return this;
    }

    /** @param port the RMI registry port; 0 (the default) picks a free one @return this */
    public AgentHostBuilder port(int port) {
        this.port = port;
        return this;
    }

    /** @param robot the robot agents here drive, or {@code null} for none @return this */
    public AgentHostBuilder robot(Robot robot) {
        this.robot = robot;
        return this;
    }

    /**
     * Where the host's own messaging node receives; without this (and without
     * {@link #noMessaging()}) it receives at {@code tcp://BIND:0}, a free port on the host's
     * bind address. Agents here use it through {@code context().messaging()}.
     *
     * @param address a messaging address, for example {@code tcp://127.0.0.1:7000}
     * @return this
     */
    public AgentHostBuilder messaging(String address) {
        this.messagingAddress = Objects.requireNonNull(address, "address");
        this.withMessaging = true;
        return this;
    }

    /** @param settings the settings of the host's own messaging node (its allow-list, timeouts, TLS) @return this */
    public AgentHostBuilder messagingSettings(MessagingSettings settings) {
        this.messagingSettings = Objects.requireNonNull(settings, "settings");
        return this;
    }

    /**
     * Agents here use this node (which the caller keeps and closes) instead of one of the host's own.
     *
     * @param node the node
     * @return this
     */
    public AgentHostBuilder messagingNode(MessagingNode node) {
        this.node = Objects.requireNonNull(node, "node");
        this.withMessaging = true;
        return this;
    }

    /** The host gives its agents no messaging (a home that only receives results). @return this */
    public AgentHostBuilder noMessaging() {
        this.withMessaging = false;
        this.node = null;
        return this;
    }

    /**
     * @param policy where whatever the host's threads catch goes (default
     *               {@link FailurePolicy#logging()}): its agent runners (an agent's callback that
     *               throws fails its stop, and is reported as survived; an error no thread
     *               survives ends the agent's trip, naming it and this host, and the runner, while
     *               the host serves on), its agent wire's accept and connection loops, its
     *               deliveries to homes, and its own messaging node's threads
     * @return this
     */
    public AgentHostBuilder failures(FailurePolicy policy) {
        this.failures = Objects.requireNonNull(policy, "policy");
        return this;
    }

    /** @param key the cluster key every peer must prove @return this */
    public AgentHostBuilder clusterKey(ClusterKey key) {
        this.key = key;
        return this;
    }

    /** @param tls mutual TLS for the RMI endpoint, or {@code null} @return this */
    public AgentHostBuilder tls(TlsSettings tls) {
        this.tls = tls;
        return this;
    }

    /** @param dir keep accepted agents durably in this directory (a journal), surviving a kill @return this */
    public AgentHostBuilder store(Path dir) {
        this.storeDir = dir;
        return this;
    }

    /** Keeps agents in memory only (the default): fast, lost if the host is killed. @return this */
    public AgentHostBuilder memoryStore() {
        this.storeDir = null;
        return this;
    }

    /** @param classNames classes agent state may hold besides the agent's own code and JDK value types @return this */
    public AgentHostBuilder allow(List<String> classNames) {
        this.allowed = List.copyOf(classNames);
        return this;
    }

    /** @param bytes the largest agent state (and array in it) accepted @return this */
    public AgentHostBuilder maxStateBytes(long bytes) {
        this.maxStateBytes = bytes;
        return this;
    }

    /** @param timeout how long a call to another host may take @return this */
    public AgentHostBuilder callTimeout(Duration timeout) {
        this.callTimeout = timeout;
        return this;
    }

    /**
     * @param policy how reports and results owed to homes that do not answer are retried, and
     *               after how long they are given up (default {@link DeliveryPolicy#defaults()})
     * @return this
     */
    public AgentHostBuilder deliveryPolicy(DeliveryPolicy policy) {
        this.delivery = Objects.requireNonNull(policy, "policy");
        return this;
    }

    /**
     * @param grace how long {@link AgentHost#close()} lets the stops running then finish before it
     *              interrupts them (default 5 s); with a durable store an interrupted stop is
     *              resumed after it at the next start, not run again
     * @return this
     */
    public AgentHostBuilder stopGrace(Duration grace) {
        if (grace.isNegative()) {
            throw new IllegalArgumentException("stop grace " + grace + " is negative: it is how long running stops may finish when the host closes");
        }
        this.stopGrace = grace;
        return this;
    }

    /**
     * @param spin how long a runner thread with nothing to do spins for the next agent before it
     *             parks (default 150 µs; zero, the default on a machine with one processor, never
     *             spins): an agent handed to a spinning runner starts at once, where waking a parked
     *             thread takes tens of microseconds on a virtual machine. Bounded: a runner spins at
     *             most this long after each stop, then parks
     * @return this
     */
    public AgentHostBuilder runnerSpin(Duration spin) {
        if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
            throw new IllegalArgumentException("runner spin " + spin + " must be between 0 and 10 ms: a spinning runner holds a processor");
        }
        this.runnerSpin = spin;
        return this;
    }

    /**
     * @param spin how long a connection thread of the host's endpoint spins for the next call
     *             before it blocks reading (default 0: never; plain sockets only)
     * @return this
     */
    public AgentHostBuilder endpointSpin(Duration spin) {
        if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
            throw new IllegalArgumentException("endpoint spin " + spin + " must be between 0 and 10 ms: a spinning connection thread holds a processor");
        }
        this.endpointSpin = spin;
        return this;
    }

    /**
     * @param on whether the host takes transfers on its agent wire (agent protocol version 3,
     *           docs/agents.md "Wire and store formats"; the default) and sends them on other
     *           hosts' wires; off, every call goes over RMI (version 2) and no wire port is opened
     * @return this
     */
    public AgentHostBuilder wire(boolean on) {
        this.wire = on;
        return this;
    }

    /**
     * @param port the port of the host's agent wire, on its bind address; 0 (the default) picks a
     *             free one. The host names it to each peer when the peer authenticates, so only a
     *             firewall needs to know it (a peer that cannot reach it sends over RMI)
     * @return this
     */
    public AgentHostBuilder wirePort(int port) {
        if (port < 0 || port > 65535) {
            throw new IllegalArgumentException("wire port " + port + " is not a TCP port");
        }
        this.wirePort = port;
        return this;
    }

    /**
     * @param spin how long a transfer this host sends on the agent wire spins (yielding the
     *             processor) for the acknowledgement before it blocks reading it (default 50 µs;
     *             zero, the default on a machine with one processor, never spins; plain connections only)
     * @return this
     */
    public AgentHostBuilder wireSpin(Duration spin) {
        if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
            throw new IllegalArgumentException("wire spin " + spin + " must be between 0 and 10 ms: a spinning sender holds a processor");
        }
        this.wireSpin = spin;
        return this;
    }

    /**
     * @param spin how long a connection thread of the host's agent wire spins (yielding the
     *             processor) for the next transfer before it blocks reading (default 0: never;
     *             plain connections only)
     * @return this
     */
    public AgentHostBuilder wireReadSpin(Duration spin) {
        if (spin.isNegative() || spin.compareTo(Duration.ofMillis(10)) > 0) {
            throw new IllegalArgumentException("wire read spin " + spin + " must be between 0 and 10 ms: a spinning connection thread holds a processor");
        }
        this.wireReadSpin = spin;
        return this;
    }

    /**
     * Lets this host's links talk to hosts of builds before agent protocol version 4 (for a
     * cluster upgraded host by host): a link to a host that refuses version 4 authenticates with
     * version 3, or 2, whose authentication does not bind the channel, so a relay between the two
     * hosts goes unnoticed (docs/security.md). Off by default: such a link fails, saying why.
     * (Hosts of builds from version 4 on need no such leave: a link to a host that does not read the
     * compact form of agent state, protocol version 5, sends it agents in the standard form.)
     *
     * @return this
     */
    public AgentHostBuilder olderHosts() {
        this.olderHosts = true;
        return this;
    }

    /**
     * For tests of mixed versions: the host acts as one of a build before the compact form of agent
     * state (protocol versions up to 4; it writes the standard form and refuses the compact one).
     */
    AgentHostBuilder beforeCompactForm() {
        this.beforeCompactForm = true;
        return this;
    }

    /** For tests of mixed versions: the host acts as one of a build before the agent wire (protocol version 2 only, no wire). */
    AgentHostBuilder version2Only() {
        this.version2Only = true;
        return this;
    }

    /** For tests: what makes the agent wire's connection threads (one that fails, to see the wire end cleanly). */
    AgentHostBuilder wireThreads(java.util.concurrent.ThreadFactory factory) {
        this.wireThreads = factory;
        return this;
    }

    /** For tests: the agent wire's limits. */
    AgentHostBuilder wireLimits(WireServer.Limits limits) {
        this.wireLimits = limits;
        return this;
    }

    /**
     * Starts the host: opens its store, resumes the agents it holds, and binds its RMI endpoint.
     *
     * @return the running host
     * @throws IOException if the store or the port cannot be used
     */
    public AgentHost start() throws IOException {
        if (key == null && tls == null) {
            throw new IllegalStateException("agent host " + name + " needs a cluster key or TLS: a host must only trust authenticated peers");
        }
        if (key == null) {
            key = ClusterKey.tlsOnly();
        }
        String atBroker = null;
        if (withMessaging && node == null) {
            try {
                String address = messagingAddress != null ? messagingAddress : "tcp://" + (bind.contains(":") ? "[" + bind + "]" : bind) + ":0";
                MessagingNode.Builder nb = MessagingNode.builder(name).settings(messagingSettings).failures(failures);
                if (address.startsWith("mqtt://") || address.startsWith("mqtts://")) {
                    atBroker = address; // joined once the host's address is known (HostMessaging.joinWhenStarted)
                } else {
                    nb.bind(address);
                }
                node = nb.build();
                ownsNode = true;
            } catch (MessagingException e) {
                throw new IOException("agent host " + name + " cannot start its messaging node: " + e.getMessage(), e);
            }
        }
        AgentHost host;
        try {
            host = new AgentHost(this);
        } catch (RuntimeException e) {
            if (ownsNode) {
                node.close();
            }
            throw e;
        }
        if (atBroker != null) {
            host.joinWhenStarted(atBroker);
        }
        try {
            host.open();
        } catch (io.robomw.api.MessagingException e) {
            host.close();
            throw new IOException("agent host " + name + " cannot start its messaging node: " + e.getMessage(), e);
        } catch (IOException | RuntimeException e) {
            host.close();
            throw e;
        }
        return host;
    }
}
