package io.robomw.agents.host;

import java.io.DataInput;
import java.io.IOException;
import java.net.InetAddress;
import java.net.NetworkInterface;
import java.net.SocketException;
import java.net.UnknownHostException;
import java.nio.ByteBuffer;

/**
 * The address a peer meant to reach, as it names it in a version-4 authentication request
 * ({@link Session#BOUND_VERSION}): the IP address and port of the host's RMI address as the peer
 * resolved them. Both proofs cover it, and the host refuses a target that is not its own address,
 * so a relay between a peer and a host is found out (docs/security.md).
 *
 * <pre>
 * [address length 1: 4 (IPv4) or 16 (IPv6)][address][port: u16]
 * </pre>
 *
 * @param address the IP address
 * @param port    the port
 */
record Target(InetAddress address, int port) {

    /** @return the peer's target for a host address: its host resolved now */
    static Target of(HostAddress host) throws UnknownHostException {
        return new Target(InetAddress.getByName(host.host()), host.port());
    }

    /** @return its wire form */
    byte[] bytes() {
        byte[] a = address.getAddress();
        return ByteBuffer.allocate(1 + a.length + 2).put((byte) a.length).put(a).putShort((short) port).array();
    }

    /**
     * Reads a target.
     *
     * @throws IOException naming what is wrong if the address length is neither 4 nor 16, or the request ends early
     */
    static Target read(DataInput in) throws IOException {
        int length = in.readUnsignedByte();
        if (length != 4 && length != 16) {
            throw new IOException("its target address has " + length + " bytes; an IPv4 address has 4, an IPv6 address 16");
        }
        byte[] a = new byte[length];
        in.readFully(a);
        return new Target(InetAddress.getByAddress(a), in.readUnsignedShort());
    }

    /**
     * Whether this is an address of a host bound to {@code bind} and listening on {@code port}: the
     * port is its port, and the address its bind address (or, for a host bound to the wildcard
     * address, any address of this machine).
     */
    boolean reaches(InetAddress bind, int hostPort) {
        if (port != hostPort) {
            return false;
        }
        if (!bind.isAnyLocalAddress()) {
            return bind.equals(address);
        }
        try {
            return address.isLoopbackAddress() || NetworkInterface.getByInetAddress(address) != null;
        } catch (SocketException e) {
            return false;
        }
    }

    @Override
    public String toString() {
        return (address.getAddress().length == 16 ? "[" + address.getHostAddress() + "]" : address.getHostAddress()) + ":" + port;
    }
}
