package io.robomw.console.server;

import java.net.InetAddress;
import java.net.NetworkInterface;
import java.net.SocketException;
import java.net.UnknownHostException;
import java.util.Collections;
import java.util.Locale;
import java.util.Set;
import java.util.TreeSet;
import java.util.function.IntSupplier;

/**
 * Which {@code Host} a request to the console may name: its own names only, so a page of another
 * site whose name was made to resolve to this machine (DNS rebinding) cannot read the console.
 * The names: {@code 127.0.0.1}, {@code localhost} and {@code [::1]}, the address or name
 * {@code --bind} gave, and for a console bound to every interface ({@code 0.0.0.0}) this
 * machine's addresses and host name; with the console's port (a request for port 80 may leave it
 * out). Anything else is refused before it is served. The Foxglove WebSocket server checks its
 * handshakes the same way.
 */
public final class HostCheck {

    private final Set<String> names;
    private final IntSupplier port;

    /**
     * @param bind the address the console listens on, as given
     * @param port its port, once it listens
     */
    public HostCheck(String bind, IntSupplier port) {
        this.port = port;
        Set<String> n = new TreeSet<>();
        n.add("127.0.0.1");
        n.add("localhost");
        n.add("[::1]");
        n.add(bracketed(bind.toLowerCase(Locale.ROOT)));
        try {
            InetAddress b = InetAddress.getByName(bind);
            n.add(bracketed(b.getHostAddress()));
            if (b.isAnyLocalAddress()) {
                for (NetworkInterface i : Collections.list(NetworkInterface.getNetworkInterfaces())) {
                    for (InetAddress a : Collections.list(i.getInetAddresses())) {
                        n.add(bracketed(a.getHostAddress().replaceFirst("%.*$", "")));
                    }
                }
                InetAddress local = InetAddress.getLocalHost();
                n.add(local.getHostName().toLowerCase(Locale.ROOT));
                n.add(local.getCanonicalHostName().toLowerCase(Locale.ROOT));
            }
        } catch (UnknownHostException | SocketException e) {
            // the names above stay
        }
        n.remove("[0.0.0.0]");
        n.remove("0.0.0.0");
        n.remove("[::]");
        this.names = Collections.unmodifiableSet(n);
    }

    private static String bracketed(String host) {
        return host.contains(":") && !host.startsWith("[") ? "[" + host + "]" : host;
    }

    /**
     * @param host a request's {@code Host} header, or {@code null}
     * @return whether it names this console
     */
    public boolean allows(String host) {
        if (host == null || host.isBlank()) {
            return false;
        }
        String h = host.strip().toLowerCase(Locale.ROOT);
        int colon = h.lastIndexOf(':');
        String name = h;
        int p = 80;
        if (colon > h.lastIndexOf(']')) {
            name = h.substring(0, colon);
            try {
                p = Integer.parseInt(h.substring(colon + 1));
            } catch (NumberFormatException e) {
                return false;
            }
        }
        return p == port.getAsInt() && names.contains(name);
    }

    /** @return the names it takes, for a refusal */
    public Set<String> names() {
        return names;
    }
}
