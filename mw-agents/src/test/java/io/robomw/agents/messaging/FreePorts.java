package io.robomw.agents.messaging;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;

/** Free loopback ports for tests that must agree on a port before binding (multicast groups). */
public final class FreePorts {

    private FreePorts() {
    }

    /** @return the name of the loopback interface ({@code lo} on Linux), for multicast in tests */
    public static String loopbackInterface() {
        try {
            return java.net.NetworkInterface.getByInetAddress(InetAddress.getLoopbackAddress()).getName();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** @return a UDP port that was free on 127.0.0.1 a moment ago */
    public static int udp() {
        try (DatagramSocket s = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0))) {
            return s.getLocalPort();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
