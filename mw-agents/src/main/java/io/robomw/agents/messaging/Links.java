package io.robomw.agents.messaging;

import io.robomw.agents.messaging.spi.Channel;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.api.MessagingException;

import java.io.IOException;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.Consumer;
import java.util.function.Function;

/**
 * The links a node opened, by host address: opened on first use, one at a time per address (a
 * slow connect to one host does not hold up the others), forgotten when they close. Also parses
 * host texts once, since senders name the same few hosts over and over. Thread-safe.
 */
final class Links {

    private static final int MAX_PARSED = 1024;

    private final String node;
    private final Function<String, Transport> transports;
    private final Consumer<Link> opened;
    private final Map<String, Link> links = new ConcurrentHashMap<>();
    private final Map<String, Object> locks = new ConcurrentHashMap<>();
    private final Map<String, Address> parsed = new ConcurrentHashMap<>();
    private final Map<Address, String> keys = new ConcurrentHashMap<>();
    private volatile boolean closed;

    /**
     * @param node       the node's name, for messages
     * @param transports the transport of a scheme
     * @param opened     told of each new link (the node sends it its subscriptions)
     */
    Links(String node, Function<String, Transport> transports, Consumer<Link> opened) {
        this.node = node;
        this.transports = transports;
        this.opened = opened;
    }

    /** @return the parsed address of a host text */
    Address parse(String host) {
        Address a = parsed.get(host);
        if (a == null) {
            a = Address.parse(host);
            if (parsed.size() > MAX_PARSED) {
                parsed.clear();
            }
            parsed.put(host, a);
        }
        return a;
    }

    /** @return how the address names its host in replies and waits (without the query) */
    String key(Address address) {
        return keys.computeIfAbsent(address, Address::toString);
    }

    /**
     * @param address a host
     * @return the open link to it, opened now if there is none
     * @throws MessagingException if it cannot be reached, or the node is closed
     */
    Link link(Address address) {
        if (closed) {
            throw new MessagingException("node '" + node + "' is closed");
        }
        String key = key(address);
        Link existing = links.get(key);
        if (existing != null && existing.isOpen()) {
            return existing;
        }
        synchronized (locks.computeIfAbsent(key, k -> new Object())) {
            existing = links.get(key);
            if (existing != null && existing.isOpen()) {
                return existing;
            }
            try {
                Link l = transports.apply(address.scheme()).connect(address);
                links.put(key, l);
                opened.accept(l);
                return l;
            } catch (IOException e) {
                throw new MessagingException("node '" + node + "' cannot reach " + address + ": " + e.getMessage(), e);
            }
        }
    }

    /** @return the link to a host, if one is open */
    Link find(String key) {
        Link l = links.get(key);
        return l != null && l.isOpen() ? l : null;
    }

    /** @return the open links that carry datagrams to one peer (UDP): they need subscriptions repeated */
    List<Link> datagramPeers() {
        List<Link> out = new ArrayList<>();
        for (Link l : links.values()) {
            if (!l.isConnection() && !l.address().scheme().equals("multicast")) {
                out.add(l);
            }
        }
        return out;
    }

    /**
     * Forgets a channel that closed, if it is one of these links.
     *
     * @return the host keys it was the link of
     */
    List<String> forget(Channel channel) {
        List<String> hosts = new ArrayList<>();
        for (Map.Entry<String, Link> e : links.entrySet()) {
            if (e.getValue() == channel && links.remove(e.getKey(), e.getValue())) {
                hosts.add(e.getKey());
            }
        }
        return hosts;
    }

    /** Forgets and closes a link that failed. */
    void drop(Link link) {
        links.remove(key(link.address()), link);
        link.close();
    }

    /** Forgets every link (the transports close them). */
    void close() {
        closed = true;
        links.clear();
    }
}
