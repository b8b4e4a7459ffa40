package io.robomw.agents.messaging.multicast;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.Transport;
import io.robomw.agents.messaging.spi.TransportContext;
import io.robomw.agents.messaging.udp.DatagramPort;
import io.robomw.agents.messaging.udp.UdpPeer;

import java.io.IOException;
import java.net.Inet4Address;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.NetworkInterface;
import java.net.SocketException;
import java.net.StandardProtocolFamily;
import java.net.StandardSocketOptions;
import java.nio.channels.DatagramChannel;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * IPv4 multicast for one node. Joining a group ({@link #bind}) opens a socket bound to the group
 * and port (shared with other processes through {@code SO_REUSEADDR}) and joined on the chosen
 * interface only. Sending goes out of a separate socket bound to that interface's own address,
 * with {@code IP_MULTICAST_IF} set to it and the configured TTL; unicast answers come back to it.
 *
 * <p>The interface is never left to the system: without a setting it is the loopback interface
 * (and TTL 0). {@link NetworkInterface#supportsMulticast()} is not consulted, because it is false
 * for {@code lo} on Linux although multicast works there.
 */
final class MulticastTransport implements Transport {

    private static final int BUFFER_BYTES = 4 << 20;

    private final TransportContext context;
    private final Map<String, DatagramPort> senders = new ConcurrentHashMap<>();
    private final List<AutoCloseable> open = new CopyOnWriteArrayList<>();

    MulticastTransport(TransportContext context) {
        this.context = context;
    }

    @Override
    public Endpoint bind(Address address) throws IOException {
        Group group = group(address);
        DatagramChannel channel = DatagramChannel.open(StandardProtocolFamily.INET);
        try {
            channel.setOption(StandardSocketOptions.SO_REUSEADDR, true);
            channel.setOption(StandardSocketOptions.SO_RCVBUF, BUFFER_BYTES);
            channel.bind(new InetSocketAddress(group.address, address.port()));
            channel.join(group.address, group.nic);
        } catch (IOException e) {
            channel.close();
            throw new IOException("cannot join " + address + " on interface " + group.nic.getName() + ": " + e.getMessage(), e);
        }
        int port = ((InetSocketAddress) channel.getLocalAddress()).getPort();
        Address bound = address.withPort(port);
        DatagramPort sender = sender(group);
        DatagramPort receiver = new DatagramPort(channel, context, bound + "@" + group.nic.getName());
        InetSocketAddress groupSocket = new InetSocketAddress(group.address, port);
        Map<InetSocketAddress, UdpPeer> known = new ConcurrentHashMap<>();
        receiver.start(from -> {
            if (known.size() > 4096) {
                known.clear();
            }
            return known.computeIfAbsent(from, f -> new UdpPeer(sender, f, Address.parse("udp://" + f.getAddress().getHostAddress() + ":" + f.getPort()),
                    bound + "<-" + f.getAddress().getHostAddress() + ":" + f.getPort(), true));
        });
        open.add(receiver);
        return new Endpoint() {
            @Override
            public Address address() {
                return bound;
            }

            @Override
            public boolean broadcast(byte[] frame) throws IOException {
                sender.send(frame, groupSocket);
                return true;
            }

            @Override
            public boolean broadcasts() {
                return true;
            }

            @Override
            public void close() {
                receiver.close();
            }
        };
    }

    @Override
    public Link connect(Address address) throws IOException {
        Group group = group(address);
        DatagramPort sender = sender(group);
        return new UdpPeer(sender, new InetSocketAddress(group.address, address.port()), address, address.toString());
    }

    @Override
    public void close() {
        for (AutoCloseable c : open) {
            try {
                c.close();
            } catch (Exception e) {
                // closing anyway
            }
        }
        open.clear();
        senders.clear();
    }

    /** The group, the interface and the TTL an address asks for. */
    private record Group(InetAddress address, NetworkInterface nic, InetAddress nicAddress, int ttl) {
    }

    private Group group(Address address) throws IOException {
        InetAddress g = InetAddress.getByName(address.host());
        if (!(g instanceof Inet4Address) || !g.isMulticastAddress()) {
            throw new IOException(address + " is not an IPv4 multicast group (224.0.0.0 to 239.255.255.255; use 239.x.y.z for local use)");
        }
        String nicName = address.query().getOrDefault("interface", context.settings().multicastInterface());
        int ttl = address.query().containsKey("ttl") ? Integer.parseInt(address.query().get("ttl")) : context.settings().multicastTtl();
        NetworkInterface nic = nic(nicName);
        InetAddress nicAddress = Collections.list(nic.getInetAddresses()).stream().filter(a -> a instanceof Inet4Address).findFirst()
                .orElseThrow(() -> new IOException("interface " + nic.getName() + " has no IPv4 address for multicast"));
        return new Group(g, nic, nicAddress, ttl);
    }

    private static NetworkInterface nic(String nameOrAddress) throws IOException {
        NetworkInterface nic;
        if (nameOrAddress == null || nameOrAddress.isEmpty()) {
            nic = NetworkInterface.getByInetAddress(InetAddress.getLoopbackAddress());
        } else {
            nic = NetworkInterface.getByName(nameOrAddress);
            if (nic == null) {
                try {
                    nic = NetworkInterface.getByInetAddress(InetAddress.getByName(nameOrAddress));
                } catch (IOException e) {
                    nic = null;
                }
            }
        }
        if (nic == null) {
            throw new SocketException("no network interface '" + nameOrAddress + "' for multicast; give one of "
                    + Collections.list(NetworkInterface.getNetworkInterfaces()).stream().map(NetworkInterface::getName).toList());
        }
        return nic;
    }

    private DatagramPort sender(Group group) throws IOException {
        String key = group.nic.getName() + "/" + group.ttl;
        DatagramPort existing = senders.get(key);
        if (existing != null) {
            return existing;
        }
        synchronized (senders) {
            existing = senders.get(key);
            if (existing != null) {
                return existing;
            }
            DatagramChannel channel = DatagramChannel.open(StandardProtocolFamily.INET);
            try {
                channel.setOption(StandardSocketOptions.IP_MULTICAST_IF, group.nic);
                channel.setOption(StandardSocketOptions.IP_MULTICAST_TTL, group.ttl);
                channel.setOption(StandardSocketOptions.IP_MULTICAST_LOOP, true);
                channel.setOption(StandardSocketOptions.SO_SNDBUF, BUFFER_BYTES);
                channel.setOption(StandardSocketOptions.SO_RCVBUF, BUFFER_BYTES);
                channel.bind(new InetSocketAddress(group.nicAddress, 0));
            } catch (IOException e) {
                channel.close();
                throw new IOException("cannot open a multicast sender on " + group.nic.getName() + ": " + e.getMessage(), e);
            }
            InetSocketAddress local = (InetSocketAddress) channel.getLocalAddress();
            String label = "udp://" + local.getAddress().getHostAddress() + ":" + local.getPort();
            DatagramPort port = new DatagramPort(channel, context, label);
            Map<InetSocketAddress, UdpPeer> known = new ConcurrentHashMap<>();
            port.start(from -> known.computeIfAbsent(from, f -> new UdpPeer(port, f,
                    Address.parse("udp://" + f.getAddress().getHostAddress() + ":" + f.getPort()), "udp://" + f.getAddress().getHostAddress() + ":" + f.getPort())));
            senders.put(key, port);
            open.add(port);
            return port;
        }
    }
}
