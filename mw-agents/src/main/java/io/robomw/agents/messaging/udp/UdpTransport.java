package io.robomw.agents.messaging.udp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;

import java.io.IOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.StandardSocketOptions;
import java.nio.channels.DatagramChannel;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * UDP unicast for one node. Messages to a {@code udp://} host go out of a port this node bound
 * (so answers come back to it) or, if it bound none, out of a port opened for sending on the
 * loopback address (for a loopback destination) or any address. Thread-safe.
 */
final class UdpTransport implements Transport {

    private static final int BUFFER_BYTES = 4 << 20;

    private final TransportContext context;
    private final List<DatagramPort> ports = new CopyOnWriteArrayList<>();

    UdpTransport(TransportContext context) {
        this.context = context;
    }

    @Override
    public Endpoint bind(Address address) throws IOException {
        DatagramPort port = open(new InetSocketAddress(InetAddress.getByName(address.host()), address.port()));
        Address bound = address.withPort(port.localAddress().getPort());
        return new Endpoint() {
            @Override
            public Address address() {
                return bound;
            }

            @Override
            public void close() {
                ports.remove(port);
                port.close();
            }
        };
    }

    @Override
    public Link connect(Address address) throws IOException {
        InetSocketAddress remote = new InetSocketAddress(InetAddress.getByName(address.host()), address.port());
        DatagramPort from = null;
        for (DatagramPort p : ports) {
            InetAddress local = p.localAddress().getAddress();
            if (local.isAnyLocalAddress() || local.isLoopbackAddress() == remote.getAddress().isLoopbackAddress()) {
                from = p;
                break;
            }
        }
        if (from == null) {
            InetAddress local = remote.getAddress().isLoopbackAddress() ? remote.getAddress() : null;
            from = open(new InetSocketAddress(local, 0));
        }
        return new UdpPeer(from, remote, address, address.toString());
    }

    @Override
    public void close() {
        ports.forEach(DatagramPort::close);
        ports.clear();
    }

    private DatagramPort open(InetSocketAddress at) throws IOException {
        DatagramChannel channel = DatagramChannel.open();
        try {
            channel.setOption(StandardSocketOptions.SO_RCVBUF, BUFFER_BYTES);
            channel.setOption(StandardSocketOptions.SO_SNDBUF, BUFFER_BYTES);
            channel.bind(at);
        } catch (IOException e) {
            channel.close();
            throw new IOException("cannot bind udp://" + at.getHostString() + ":" + at.getPort() + ": " + e.getMessage(), e);
        }
        InetSocketAddress local = (InetSocketAddress) channel.getLocalAddress();
        DatagramPort port = new DatagramPort(channel, context, "udp://" + local.getHostString() + ":" + local.getPort());
        java.util.Map<InetSocketAddress, UdpPeer> known = new java.util.concurrent.ConcurrentHashMap<>();
        port.start(from -> {
            if (known.size() > 4096) {
                known.clear();
            }
            return known.computeIfAbsent(from, f -> new UdpPeer(port, f, Address.parse("udp://" + hostText(f) + ":" + f.getPort()),
                    "udp://" + hostText(f) + ":" + f.getPort()));
        });
        ports.add(port);
        return port;
    }

    static String hostText(InetSocketAddress a) {
        String h = a.getAddress().getHostAddress();
        return h.contains(":") ? "[" + h + "]" : h;
    }
}
