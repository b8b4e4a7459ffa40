package io.robomw.platform.mavlink.link;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.UnknownHostException;
import java.util.Locale;
import java.util.Objects;
import java.util.function.LongSupplier;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Where a MAVLink link goes, in MAVSDK's connection-URL forms:
 * <ul>
 *   <li>{@code udpin://HOST:PORT}: listen on that address ({@code udpin://127.0.0.1:14550} on this machine,
 *   {@code udpin://0.0.0.0:14550} on every interface); the address is never implied: MAVSDK's
 *   {@code udp://:PORT} (every interface) is refused, naming both forms;</li>
 *   <li>{@code udpout://HOST:PORT} (also {@code udp://HOST:PORT}, as SITL's {@code --out} writes it):
 *   send to that address from a free port;</li>
 *   <li>{@code serial:///dev/ttyUSB0} or {@code serial:///dev/ttyUSB0:57600}: a serial port, at
 *   {@value SerialMavlinkLink#DEFAULT_BAUD} baud unless given.</li>
 * </ul>
 *
 * @param kind   the kind of link
 * @param host   the UDP host (empty for serial)
 * @param port   the UDP port (0 for serial)
 * @param device the serial device (empty for UDP)
 * @param baud   the serial baud rate (0 for UDP)
 */
public record MavlinkEndpoint(Kind kind, String host, int port, String device, int baud) {

    private static final Pattern UDP = Pattern.compile("(udpin|udpout|udp)://(\\[[^]]+]|[^:/]*):(\\d{1,5})");
    private static final Pattern SERIAL = Pattern.compile("serial://(/[^:]+)(?::(\\d+))?");

    /** The kinds of link. */
    public enum Kind {
        /** Listen on a UDP port. */
        UDP_LISTEN,
        /** Send to a UDP address. */
        UDP_SEND,
        /** A serial port. */
        SERIAL
    }

    /** Checks the values. */
    public MavlinkEndpoint {
        Objects.requireNonNull(kind, "kind");
        Objects.requireNonNull(host, "host");
        Objects.requireNonNull(device, "device");
        if (kind != Kind.SERIAL && (port < 0 || port > 65_535 || (kind == Kind.UDP_SEND && port == 0))) {
            throw new IllegalArgumentException("a UDP port is 1-65535 (0 only to listen on a free port), got " + port);
        }
        if (kind == Kind.SERIAL && (baud < 300 || baud > 4_000_000)) {
            throw new IllegalArgumentException("a serial baud rate is 300 to 4000000, got " + baud);
        }
    }

    /**
     * @param url an endpoint URL
     * @return the endpoint
     * @throws IllegalArgumentException naming the URL and the forms allowed
     */
    public static MavlinkEndpoint parse(String url) {
        String u = url.strip();
        Matcher m = UDP.matcher(u);
        if (m.matches()) {
            String host = m.group(2).replace("[", "").replace("]", "");
            int port = Integer.parseInt(m.group(3));
            Kind kind = m.group(1).toLowerCase(Locale.ROOT).equals("udpin") ? Kind.UDP_LISTEN : Kind.UDP_SEND;
            if (host.isEmpty()) {
                // MAVSDK's udp://:14540 listens on every interface; RoboMW listens beyond this machine only when told so.
                throw new IllegalArgumentException("'" + url + "' names no address: write udpin://127.0.0.1:" + port + " to listen on this machine,"
                        + " udpin://0.0.0.0:" + port + " to listen on every interface (anyone on the network may then command the vehicle"
                        + " unless it signs), or udpout://HOST:" + port + " to send to a vehicle");
            }
            return new MavlinkEndpoint(kind, host, port, "", 0);
        }
        m = SERIAL.matcher(u);
        if (m.matches()) {
            int baud = m.group(2) == null ? SerialMavlinkLink.DEFAULT_BAUD : Integer.parseInt(m.group(2));
            return new MavlinkEndpoint(Kind.SERIAL, "", 0, m.group(1), baud);
        }
        throw new IllegalArgumentException("'" + url + "' is not a MAVLink link: write udpin://HOST:PORT (listen), udpout://HOST:PORT"
                + " or udp://HOST:PORT (send to), or serial:///dev/DEVICE[:BAUD]");
    }

    /**
     * Opens the link.
     *
     * @param nanos a monotonic clock, nanoseconds (UDP peers are forgotten by it)
     * @return the open link
     * @throws IOException naming the address or device if it cannot be opened
     */
    public MavlinkLink open(LongSupplier nanos) throws IOException {
        return switch (kind) {
            case UDP_LISTEN -> UdpMavlinkLink.listen(new InetSocketAddress(host, port), nanos);
            case UDP_SEND -> UdpMavlinkLink.sendTo(new InetSocketAddress(host, port), nanos);
            case SERIAL -> SerialMavlinkLink.open(device, baud);
        };
    }

    /** @return whether this link can be reached only from this machine (a UDP loopback address or a serial port) */
    public boolean local() {
        if (kind == Kind.SERIAL) {
            return true;
        }
        try {
            return InetAddress.getByName(host).isLoopbackAddress();
        } catch (UnknownHostException e) {
            return false;
        }
    }

    @Override
    public String toString() {
        return switch (kind) {
            case UDP_LISTEN -> "udpin://" + host + ":" + port;
            case UDP_SEND -> "udpout://" + host + ":" + port;
            case SERIAL -> "serial://" + device + ":" + baud;
        };
    }
}
