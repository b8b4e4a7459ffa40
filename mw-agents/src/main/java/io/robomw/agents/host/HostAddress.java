package io.robomw.agents.host;

import java.net.URI;

/**
 * An agent host's address, {@code rmi://host:port/name}.
 *
 * @param host the host's IP address or name
 * @param port its RMI registry port
 * @param name the name it is bound under
 */
public record HostAddress(String host, int port, String name) {

    /**
     * @param address an address such as {@code rmi://127.0.0.1:1099/nxt}
     * @return it, parsed
     * @throws IllegalArgumentException naming what is wrong with it
     */
    public static HostAddress parse(String address) {
        URI uri;
        try {
            uri = URI.create(address);
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException("'" + address + "' is not an agent host address (rmi://host:port/name): " + e.getMessage(), e);
        }
        String path = uri.getPath() == null ? "" : uri.getPath().replaceFirst("^/", "");
        if (!"rmi".equals(uri.getScheme()) || uri.getHost() == null || uri.getPort() <= 0 || path.isEmpty() || path.contains("/")) {
            throw new IllegalArgumentException("'" + address + "' is not an agent host address: expected rmi://host:port/name, for example rmi://127.0.0.1:1099/nxt");
        }
        return new HostAddress(uri.getHost(), uri.getPort(), path);
    }

    @Override
    public String toString() {
        return "rmi://" + (host.contains(":") ? "[" + host + "]" : host) + ":" + port + "/" + name;
    }
}
