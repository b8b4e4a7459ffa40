package io.robomw.agents.host;

import io.robomw.api.MessagingException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

/**
 * The agent hosts a host knows of, and where their messaging nodes receive: what lets an agent
 * address a message to a host by its name ({@code "ft"}) or its agent host address
 * ({@code rmi://127.0.0.1:1100/ft}) as well as by a messaging address ({@code tcp://...}).
 *
 * <p>A host learns of others from every address it meets (the stops of the agents it holds,
 * their homes, the peers that call it) and from their descriptions ({@code DESCRIBE}), which
 * carry the hosts they know in turn. A name it does not know is looked for by describing the
 * asking agent's home (which knows every host it sent agents to), then the hosts already known.
 *
 * <p>Thread-safe; bounded to {@value HostDescription#MAX_LIST} hosts (the oldest are forgotten).
 */
final class HostDirectory {

    private static final Logger LOG = LoggerFactory.getLogger(HostDirectory.class);
    /** Schemes whose addresses are messaging addresses already. */
    private static final Set<String> MESSAGING_SCHEMES = Set.of("tcp", "udp", "multicast", "mqtt", "mqtts");

    /** Describes the host at an address (an authenticated call). */
    @FunctionalInterface
    interface Describer {
        HostDescription describe(String hostAddress) throws PeerException;
    }

    private record KnownHost(String name, String address, List<String> messaging) {
    }

    private final String self;
    private final Map<String, KnownHost> byAddress = new LinkedHashMap<>(16, 0.75f, false) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<String, KnownHost> eldest) {
            return size() > HostDescription.MAX_LIST;
        }
    };

    /** @param self this host's own address, never listed as another host */
    HostDirectory(String self) {
        this.self = self;
    }

    /** @param hostAddress an agent host address met on the way; ignored when it is not one */
    void learn(String hostAddress) {
        if (hostAddress == null || hostAddress.equals(self)) {
            return;
        }
        HostAddress a;
        try {
            a = HostAddress.parse(hostAddress);
        } catch (IllegalArgumentException e) {
            return;
        }
        synchronized (byAddress) {
            byAddress.putIfAbsent(a.toString(), new KnownHost(a.name(), a.toString(), List.of()));
        }
    }

    /** @param d a host's description: the host itself, with its messaging addresses, and the hosts it knows */
    void learn(HostDescription d) {
        synchronized (byAddress) {
            if (!d.address().equals(self)) {
                byAddress.put(d.address(), new KnownHost(d.name(), d.address(), d.messaging()));
            }
        }
        d.known().forEach(k -> learn(k.address()));
    }

    /** @return the hosts known, for this host's own description */
    List<HostDescription.Known> known() {
        synchronized (byAddress) {
            return byAddress.values().stream().map(e -> new HostDescription.Known(e.name(), e.address())).toList();
        }
    }

    /**
     * Turns the {@code host} of a messaging call into a messaging address.
     *
     * @param host     a messaging address, an agent host's address, or an agent host's name
     * @param home     the asking agent's home, asked about names this host does not know, or {@code null}
     * @param describe how other hosts are asked
     * @return the messaging address to use
     * @throws MessagingException when a name or host address cannot be resolved, saying what is known
     */
    String resolve(String host, String home, Describer describe) {
        int scheme = host.indexOf("://");
        if (scheme > 0 && MESSAGING_SCHEMES.contains(host.substring(0, scheme))) {
            return host;
        }
        if (scheme > 0) {
            HostAddress a;
            try {
                a = HostAddress.parse(host);
            } catch (IllegalArgumentException e) {
                return host; // an RMI messaging address with a longer path, or a transport added through the SPI
            }
            KnownHost known;
            synchronized (byAddress) {
                known = byAddress.get(a.toString());
            }
            if (known == null || known.messaging().isEmpty()) {
                try {
                    learn(describe.describe(a.toString()));
                } catch (PeerException | RuntimeException e) {
                    // Not an agent host that answers: an RMI messaging endpoint is addressed the same way.
                    LOG.debug("{} did not describe itself as an agent host ({}); using it as a messaging address", host, e.toString());
                    return host;
                }
            }
            return messagingOf(a.toString(), describe).orElse(host);
        }
        return addressOfName(host, home, describe).flatMap(a -> messagingOf(a, describe)).orElseThrow(() -> new MessagingException(
                "no agent host named '" + host + "' is known here (known: " + known().stream().map(HostDescription.Known::name).toList()
                        + "); give its address (rmi://HOST:PORT/" + host + ") or its messaging address (tcp://...)"));
    }

    /**
     * The agent host address of a host given by name (as messages reach hosts by name), for an
     * agent's hop: {@code context().dispatch("lab-b")}, or a stop added by name.
     *
     * @param nameOrAddress an agent host's name, or its address ({@code rmi://host:port/name})
     * @param home          the asking agent's home, asked about names this host does not know, or {@code null}
     * @param describe      how other hosts are asked
     * @return its agent host address
     * @throws IllegalArgumentException when it is neither an agent host address nor the name of a host known here or at the home
     */
    String hostAddress(String nameOrAddress, String home, Describer describe) {
        if (nameOrAddress.contains("://")) {
            return HostAddress.parse(nameOrAddress).toString();
        }
        if (!nameOrAddress.matches("[A-Za-z0-9._-]+")) {
            throw new IllegalArgumentException("'" + nameOrAddress + "' is neither an agent host address (rmi://host:port/name) nor a host name");
        }
        return addressOfName(nameOrAddress, home, describe).orElseThrow(() -> new IllegalArgumentException("no agent host named '" + nameOrAddress
                + "' is known at " + self + " (known: " + known().stream().map(HostDescription.Known::name).toList() + "); give its address (rmi://HOST:PORT/"
                + nameOrAddress + ")"));
    }

    /** The agent host address of a name: known here, or learnt from the agent's home or the hosts known (each described in turn). */
    private Optional<String> addressOfName(String name, String home, Describer describe) {
        Optional<String> byName = byName(name);
        if (byName.isPresent()) {
            return byName;
        }
        List<String> askNext = new ArrayList<>();
        if (home != null && !home.equals(self)) {
            askNext.add(home);
        }
        askNext.addAll(addresses());
        for (String peer : askNext) {
            tryDescribe(peer, describe);
            byName = byName(name);
            if (byName.isPresent()) {
                return byName;
            }
        }
        return Optional.empty();
    }

    private Optional<String> byName(String name) {
        List<String> matching;
        synchronized (byAddress) {
            matching = byAddress.values().stream().filter(e -> e.name().equals(name)).map(KnownHost::address).toList();
        }
        if (matching.size() > 1) {
            throw new MessagingException("more than one agent host is named '" + name + "': " + matching + "; give the address of the one you mean");
        }
        return matching.isEmpty() ? Optional.empty() : Optional.of(matching.get(0));
    }

    /** The messaging address of a known or new agent host, describing it if its messaging is not known yet. */
    private Optional<String> messagingOf(String hostAddress, Describer describe) {
        KnownHost e;
        synchronized (byAddress) {
            e = byAddress.get(hostAddress);
        }
        if (e == null || e.messaging().isEmpty()) {
            HostDescription d = describe(hostAddress, describe);
            if (d.messaging().isEmpty()) {
                throw new MessagingException("agent host " + hostAddress + " has no messaging node (it was started with --no-messaging)");
            }
            return Optional.of(preferred(d.messaging()));
        }
        return Optional.of(preferred(e.messaging()));
    }

    private HostDescription describe(String hostAddress, Describer describe) {
        try {
            HostDescription d = describe.describe(hostAddress);
            learn(d);
            return d;
        } catch (PeerException ex) {
            throw new MessagingException("agent host " + hostAddress + " cannot be asked where its messaging node is: " + ex.getMessage(), ex);
        }
    }

    private void tryDescribe(String hostAddress, Describer describe) {
        try {
            learn(describe.describe(hostAddress));
        } catch (PeerException | RuntimeException ex) {
            LOG.debug("cannot describe {}: {}", hostAddress, ex.toString());
        }
    }

    private List<String> addresses() {
        synchronized (byAddress) {
            return List.copyOf(byAddress.keySet());
        }
    }

    /** A connection-oriented address first: requests and replies want one. */
    private static String preferred(List<String> messaging) {
        return messaging.stream().filter(m -> m.startsWith("tcp://")).findFirst().orElse(messaging.get(0));
    }
}
