package io.robomw.testkit;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.ThreadLocalRandom;

/**
 * Loopback TCP ports for tests that must name a port before something binds it: a server
 * restarted at its own address, or a child process told where to listen. A port the system hands
 * out ({@code bind(0)}) comes from the ephemeral range, from which the kernel also takes the local
 * port of every outgoing connection, so on a busy machine another process's connection can hold
 * it between the choice and the bind (an agent host restarted on its port failed with "Address
 * already in use" while another build ran beside it). These ports come from below that range,
 * where only an explicit bind takes a port: chosen at random, each checked free when chosen.
 */
public final class Ports {

    /** The lowest port handed out: well above the registered services a test machine may run. */
    static final int LOWEST = 20_000;
    /** Where the ephemeral range starts when the kernel does not say (Linux's default). */
    static final int EPHEMERAL_DEFAULT = 32_768;

    private Ports() {
    }

    /**
     * @return a loopback TCP port below the ephemeral range that was free a moment ago
     * @throws UncheckedIOException if no free one was found in 200 tries
     */
    public static int free() {
        int below = ephemeralStart();
        IOException last = null;
        for (int i = 0; i < 200; i++) {
            int port = ThreadLocalRandom.current().nextInt(LOWEST, below);
            try (ServerSocket s = new ServerSocket()) {
                s.setReuseAddress(false);
                s.bind(new InetSocketAddress(InetAddress.getLoopbackAddress(), port));
                return port;
            } catch (IOException e) {
                last = e;
            }
        }
        throw new UncheckedIOException("no free loopback port between " + LOWEST + " and " + below + " in 200 tries", last);
    }

    /** The first port of the kernel's ephemeral range ({@code /proc/sys/net/ipv4/ip_local_port_range}), or Linux's default. */
    static int ephemeralStart() {
        try {
            String[] range = Files.readString(Path.of("/proc/sys/net/ipv4/ip_local_port_range")).trim().split("\\s+");
            int start = Integer.parseInt(range[0]);
            return start > LOWEST + 1_000 ? start : EPHEMERAL_DEFAULT;
        } catch (IOException | RuntimeException e) {
            return EPHEMERAL_DEFAULT;
        }
    }
}
