package io.robomw.agents.messaging;

import java.net.URI;
import java.net.URISyntaxException;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;

/**
 * A messaging address: {@code tcp://host:port}, {@code udp://host:port},
 * {@code multicast://group:port}, {@code rmi://host:port/name}, {@code mqtt://broker:port[/prefix]}
 * (the port may be left out there: 1883, or 8883 for {@code mqtts://}). Settings a transport reads
 * from the address go in the query, for example {@code multicast://239.1.2.3:5000?interface=lo&ttl=0}.
 * Credentials never go in an address (it shows in process lists and logs): {@code user:secret@host}
 * is refused.
 *
 * @param scheme the transport
 * @param host   host name or address literal (IPv6 without brackets)
 * @param port   port; 0 asks the system for a free one when binding
 * @param path   the path without its leading slash (the RMI name), or empty
 * @param query  settings from the query, in order
 */
public record Address(String scheme, String host, int port, String path, Map<String, String> query) {

    /** Checks and copies. */
    public Address {
        Objects.requireNonNull(scheme, "scheme");
        Objects.requireNonNull(host, "host");
        Objects.requireNonNull(path, "path");
        if (port < 0 || port > 65535) {
            throw new IllegalArgumentException("port must be 0..65535, got " + port);
        }
        query = Map.copyOf(query);
    }

    /**
     * @param text an address such as {@code tcp://127.0.0.1:7000}
     * @return the parsed address
     * @throws IllegalArgumentException if it is not of the form scheme://host:port[/path][?key=value&amp;...]
     */
    public static Address parse(String text) {
        URI uri;
        try {
            uri = new URI(text);
        } catch (URISyntaxException e) {
            throw new IllegalArgumentException("'" + text + "' is not an address: " + e.getMessage()
                    + "; expected scheme://host:port, for example tcp://127.0.0.1:7000");
        }
        int port = uri.getPort() >= 0 || uri.getScheme() == null ? uri.getPort() : defaultPort(uri.getScheme());
        if (uri.getScheme() == null || uri.getHost() == null || port < 0) {
            throw new IllegalArgumentException("'" + text + "' is not an address: expected scheme://host:port[/name],"
                    + " for example tcp://127.0.0.1:7000, udp://127.0.0.1:7001, multicast://239.1.2.3:7002, rmi://127.0.0.1:1099/robot,"
                    + " mqtt://127.0.0.1:1883");
        }
        if (uri.getRawUserInfo() != null) {
            throw new IllegalArgumentException("'" + uri.getScheme() + "://" + uri.getHost() + ":" + port + "': credentials do not go in an address,"
                    + " where process lists and logs would show them; give them in a file or the environment (docs/messaging.md)");
        }
        String host = uri.getHost();
        if (host.startsWith("[") && host.endsWith("]")) {
            host = host.substring(1, host.length() - 1);
        }
        String path = uri.getPath() == null ? "" : uri.getPath();
        while (path.startsWith("/")) {
            path = path.substring(1);
        }
        Map<String, String> query = new LinkedHashMap<>();
        if (uri.getQuery() != null) {
            for (String pair : uri.getQuery().split("&")) {
                if (pair.isEmpty()) {
                    continue;
                }
                int eq = pair.indexOf('=');
                query.put(eq < 0 ? pair : pair.substring(0, eq), eq < 0 ? "" : pair.substring(eq + 1));
            }
        }
        return new Address(uri.getScheme().toLowerCase(java.util.Locale.ROOT), host, port, path, query);
    }

    /** The port of a scheme whose standard gives one (MQTT: 1883, over TLS 8883), else -1. */
    private static int defaultPort(String scheme) {
        return switch (scheme.toLowerCase(java.util.Locale.ROOT)) {
            case "mqtt" -> 1883;
            case "mqtts" -> 8883;
            default -> -1;
        };
    }

    /**
     * @param newPort a port
     * @return this address with that port (to report the port a bind chose)
     */
    public Address withPort(int newPort) {
        return new Address(scheme, host, newPort, path, query);
    }

    /**
     * @param newPath a path
     * @return this address with that path and no query
     */
    public Address withPath(String newPath) {
        return new Address(scheme, host, port, newPath, Map.of());
    }

    /** @return scheme, host and port: the address of the endpoint without path or query */
    public String endpoint() {
        String h = host.contains(":") ? "[" + host + "]" : host;
        return scheme + "://" + h + ":" + port;
    }

    /** @return the address without its query, which is how hosts are compared */
    @Override
    public String toString() {
        return path.isEmpty() ? endpoint() : endpoint() + "/" + path;
    }
}
