package io.robomw.platform.mavlink.link;

import io.robomw.platform.mavlink.wire.FrameDecoder;
import io.robomw.platform.mavlink.wire.Frame;

import java.io.IOException;
import java.net.DatagramPacket;
import java.net.DatagramSocket;
import java.net.InetSocketAddress;
import java.net.SocketAddress;
import java.net.SocketException;
import java.net.SocketTimeoutException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.function.LongSupplier;

/**
 * MAVLink over UDP, the way ground stations and autopilots use it: each datagram carries whole
 * frames. Two modes, as MAVSDK names them:
 * <ul>
 *   <li><b>listen</b> ({@code udpin://HOST:PORT}): bound to a port, it answers whoever sends to it.
 *   Every sender of a good frame becomes a peer, and {@link #send} goes to each peer heard from
 *   within {@link #PEER_TIMEOUT} (at most {@value #MAX_PEERS}, the least recently heard
 *   forgotten first). A ground station listening on 14550 hears the vehicle that sends there
 *   (ArduPilot SITL's {@code --out}); a vehicle listening on its port answers every ground station
 *   that talks to it, as mavlink-router does.</li>
 *   <li><b>send</b> ({@code udpout://HOST:PORT}): bound to a free port, it sends to one address and
 *   reads what comes back (also from others: their frames are received, and they become peers).</li>
 * </ul>
 * A datagram with bytes that are not frames is skipped; a frame cut at a datagram's end is dropped
 * ({@link FrameDecoder#feedDatagram}).
 *
 * <p>Threads: one receiver; {@link #send} from any thread ({@link DatagramSocket#send} is).
 */
public final class UdpMavlinkLink implements MavlinkLink {

    /** How long a peer that is not heard from is still sent to. */
    public static final Duration PEER_TIMEOUT = Duration.ofSeconds(10);
    /** The most peers sent to at once. */
    public static final int MAX_PEERS = 16;

    private final DatagramSocket socket;
    private final InetSocketAddress target;
    private final LongSupplier nanos;
    private final byte[] buffer = new byte[65_536];
    private final Map<SocketAddress, Long> peers = new LinkedHashMap<>(16, 0.75f, true);
    private final FrameDecoder decoder;
    private SocketAddress current;
    private final List<Frame> received = new ArrayList<>();

    private UdpMavlinkLink(DatagramSocket socket, InetSocketAddress target, LongSupplier nanos) {
        this.socket = socket;
        this.target = target;
        this.nanos = nanos;
        this.decoder = new FrameDecoder(received::add);
    }

    /**
     * Listens on a port.
     *
     * @param bind  the address and port to bind ({@code 127.0.0.1:14550}; port 0 picks a free one)
     * @param nanos a monotonic clock, nanoseconds (peers are forgotten by it)
     * @return the link
     * @throws IOException naming the address if it cannot be bound
     */
    public static UdpMavlinkLink listen(InetSocketAddress bind, LongSupplier nanos) throws IOException {
        return new UdpMavlinkLink(bound(bind), null, nanos);
    }

    /**
     * Sends to one address from a free port.
     *
     * @param target where frames go
     * @param nanos  a monotonic clock, nanoseconds
     * @return the link
     * @throws IOException if no socket can be had
     */
    public static UdpMavlinkLink sendTo(InetSocketAddress target, LongSupplier nanos) throws IOException {
        Objects.requireNonNull(target, "target");
        if (target.isUnresolved()) {
            throw new IOException("udp: cannot resolve the host " + target.getHostString());
        }
        InetSocketAddress bind = new InetSocketAddress(target.getAddress().isLoopbackAddress() ? target.getAddress() : null, 0);
        return new UdpMavlinkLink(bound(bind), target, nanos);
    }

    private static DatagramSocket bound(InetSocketAddress bind) throws IOException {
        DatagramSocket s = new DatagramSocket(null);
        try {
            s.setReuseAddress(false);
            s.bind(bind);
            return s;
        } catch (SocketException e) {
            s.close();
            throw new IOException("udp: cannot bind " + bind + ": " + e.getMessage(), e);
        }
    }

    /** @return the bound local address */
    public InetSocketAddress localAddress() {
        return (InetSocketAddress) socket.getLocalSocketAddress();
    }

    /** @return the fixed target, if this link sends to one */
    public java.util.Optional<InetSocketAddress> target() {
        return java.util.Optional.ofNullable(target);
    }

    /** @return the peers heard from recently, most recent last */
    public synchronized List<SocketAddress> peers() {
        forgetSilentPeers();
        return List.copyOf(peers.keySet());
    }

    @Override
    public boolean send(byte[] frame) throws IOException {
        List<SocketAddress> to = new ArrayList<>(2);
        if (target != null) {
            to.add(target);
        }
        synchronized (this) {
            forgetSilentPeers();
            for (SocketAddress p : peers.keySet()) {
                if (!p.equals(target)) {
                    to.add(p);
                }
            }
        }
        if (to.isEmpty()) {
            return false;
        }
        for (SocketAddress a : to) {
            try {
                socket.send(new DatagramPacket(frame, frame.length, a));
            } catch (IOException e) {
                if (socket.isClosed()) {
                    throw new IOException(describe() + " is closed", e);
                }
                // An unreachable peer (ICMP) must not stop the others: it is forgotten when it stays silent.
                if (a.equals(target)) {
                    throw new IOException(describe() + ": sending to " + a + " failed: " + e.getMessage(), e);
                }
            }
        }
        return true;
    }

    private void forgetSilentPeers() {
        long now = nanos.getAsLong();
        peers.values().removeIf(heard -> now - heard > PEER_TIMEOUT.toNanos());
    }

    @Override
    public int receive(Duration timeout, FrameSink sink) throws IOException {
        DatagramPacket p = new DatagramPacket(buffer, buffer.length);
        try {
            socket.setSoTimeout((int) Math.max(1, Math.min(Integer.MAX_VALUE, timeout.toMillis())));
            socket.receive(p);
        } catch (SocketTimeoutException e) {
            return 0;
        } catch (IOException e) {
            throw new IOException(describe() + (socket.isClosed() ? " is closed" : ": " + e.getMessage()), e);
        }
        received.clear();
        decoder.feedDatagram(p.getData(), p.getOffset(), p.getLength());
        if (received.isEmpty()) {
            return 0;
        }
        SocketAddress from = p.getSocketAddress();
        synchronized (this) {
            peers.put(from, nanos.getAsLong());
            while (peers.size() > MAX_PEERS) {
                SocketAddress eldest = peers.keySet().iterator().next();
                peers.remove(eldest);
            }
            current = from;
        }
        int n = received.size();
        for (Frame f : List.copyOf(received)) {
            sink.frame(f, from);
        }
        return n;
    }

    /** @return the decoder's counts (frames, bad bytes) */
    public FrameDecoder.Counts counts() {
        return decoder.counts();
    }

    /** @return the peer the last frame came from, or {@code null} */
    public synchronized SocketAddress lastPeer() {
        return current;
    }

    @Override
    public String describe() {
        InetSocketAddress local = localAddress();
        String l = local == null ? "(closed)" : local.getAddress().getHostAddress() + ":" + local.getPort();
        return target == null ? "udp listening on " + l : "udp " + l + " to " + target.getAddress().getHostAddress() + ":" + target.getPort();
    }

    @Override
    public void close() {
        socket.close();
    }
}
