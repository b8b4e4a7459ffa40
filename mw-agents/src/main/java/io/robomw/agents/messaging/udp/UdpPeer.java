package io.robomw.agents.messaging.udp;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.spi.Link;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.util.Objects;

/**
 * A datagram peer: a local {@link DatagramPort} and a remote socket address. Used both as the link
 * to an address this node sends to and as the channel answers go back on. Two peers are equal
 * when they send from the same port to the same address. Closing forgets nothing: there is no
 * connection.
 */
public final class UdpPeer implements Link {

    private final DatagramPort port;
    private final InetSocketAddress remote;
    private final Address address;
    private final String label;
    private final boolean group;

    /**
     * @param port    the local port frames go out of
     * @param remote  the peer's socket address
     * @param address the peer's address as the node names it
     * @param label   how logs and loss counters name this peer
     */
    public UdpPeer(DatagramPort port, InetSocketAddress remote, Address address, String label) {
        this(port, remote, address, label, false);
    }

    /**
     * @param port    the local port frames go out of
     * @param remote  the peer's socket address
     * @param address the peer's address as the node names it
     * @param label   how logs and loss counters name this peer
     * @param group   whether its frames came through a multicast group
     */
    public UdpPeer(DatagramPort port, InetSocketAddress remote, Address address, String label, boolean group) {
        this.group = group;
        this.port = port;
        this.remote = remote;
        this.address = address;
        this.label = label;
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public String peer() {
        return label;
    }

    @Override
    public void send(byte[] frame) throws IOException {
        port.send(frame, remote);
    }

    @Override
    public int maxFrameBytes() {
        return port.maxFrameBytes();
    }

    @Override
    public boolean isOpen() {
        return true;
    }

    @Override
    public boolean isConnection() {
        return false;
    }

    @Override
    public boolean deliversOn(Thread thread) {
        return port.isReader(thread);
    }

    @Override
    public boolean isGroup() {
        return group;
    }

    @Override
    public void close() {
        // datagrams have no connection to close
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof UdpPeer p && p.port == port && p.remote.equals(remote);
    }

    @Override
    public int hashCode() {
        return Objects.hash(System.identityHashCode(port), remote);
    }

    @Override
    public String toString() {
        return "UdpPeer[" + label + "]";
    }
}
