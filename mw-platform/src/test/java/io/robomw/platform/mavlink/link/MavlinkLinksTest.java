package io.robomw.platform.mavlink.link;

import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.PseudoTerminal;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameDecoder;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.io.OutputStream;
import java.io.UncheckedIOException;
import java.net.DatagramPacket;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.SocketAddress;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicLong;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The links on real sockets and a real pseudo-terminal, loopback only. */
class MavlinkLinksTest {

    private static final Duration WAIT = Duration.ofSeconds(5);
    private static final InetSocketAddress ANY_LOOPBACK_PORT = new InetSocketAddress(InetAddress.getLoopbackAddress(), 0);

    private static byte[] heartbeat(FrameEncoder e, int customMode) {
        return e.encode(Payload.of(Messages.Heartbeat.MESSAGE).set(Messages.Heartbeat.CUSTOM_MODE, customMode));
    }

    /** Receives until a frame comes (each receive waits up to 200 ms for bytes). */
    private static List<Frame> receiveOne(MavlinkLink link, List<SocketAddress> from) {
        List<Frame> out = new ArrayList<>();
        Await.until("a frame on " + link.describe(), WAIT, () -> {
            try {
                link.receive(Duration.ofMillis(200), (f, a) -> {
                    out.add(f);
                    from.add(a);
                });
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
            return !out.isEmpty();
        });
        return out;
    }

    @Test
    void aListeningLinkAnswersWhoeverSentToIt() throws IOException {
        try (UdpMavlinkLink vehicle = UdpMavlinkLink.listen(ANY_LOOPBACK_PORT, System::nanoTime);
             UdpMavlinkLink gcs = UdpMavlinkLink.sendTo(vehicle.localAddress(), System::nanoTime)) {
            FrameEncoder vehicleEncoder = new FrameEncoder(1, 1);
            assertFalse(vehicle.send(heartbeat(vehicleEncoder, 1)), "nobody to send to yet");
            assertTrue(gcs.send(heartbeat(new FrameEncoder(255, 190), 0)));
            List<SocketAddress> from = new ArrayList<>();
            List<Frame> got = receiveOne(vehicle, from);
            assertEquals(255, got.get(0).systemId());
            assertEquals(gcs.localAddress(), from.get(0));
            assertTrue(vehicle.send(heartbeat(vehicleEncoder, 4)));
            List<Frame> back = receiveOne(gcs, new ArrayList<>());
            assertEquals(4, back.get(0).payload().getLong(Messages.Heartbeat.CUSTOM_MODE));
        }
    }

    @Test
    void garbageInADatagramIsSkippedAndFramesBesideItAreRead() throws IOException {
        try (UdpMavlinkLink gcs = UdpMavlinkLink.listen(ANY_LOOPBACK_PORT, System::nanoTime);
             DatagramSocket raw = new DatagramSocket(ANY_LOOPBACK_PORT)) {
            byte[] hb = heartbeat(new FrameEncoder(1, 1), 7);
            byte[] noisy = new byte[hb.length + 6];
            noisy[0] = (byte) 0xFD;
            noisy[1] = 0x40;
            System.arraycopy(hb, 0, noisy, 3, hb.length);
            raw.send(new DatagramPacket(new byte[]{1, 2, 3}, 3, gcs.localAddress()));
            raw.send(new DatagramPacket(noisy, noisy.length, gcs.localAddress()));
            List<Frame> got = receiveOne(gcs, new ArrayList<>());
            assertEquals(7, got.get(0).payload().getLong(Messages.Heartbeat.CUSTOM_MODE));
            assertTrue(gcs.counts().droppedBytes() >= 3);
            assertEquals(List.of(raw.getLocalSocketAddress()), gcs.peers(), "only a sender of a good frame is a peer");
        }
    }

    @Test
    void aSilentPeerIsForgotten() throws IOException {
        AtomicLong now = new AtomicLong();
        try (UdpMavlinkLink vehicle = UdpMavlinkLink.listen(ANY_LOOPBACK_PORT, now::get);
             UdpMavlinkLink gcs = UdpMavlinkLink.sendTo(vehicle.localAddress(), System::nanoTime)) {
            gcs.send(heartbeat(new FrameEncoder(255, 190), 0));
            receiveOne(vehicle, new ArrayList<>());
            assertEquals(1, vehicle.peers().size());
            now.addAndGet(UdpMavlinkLink.PEER_TIMEOUT.toNanos() + 1);
            assertEquals(List.of(), vehicle.peers());
            assertFalse(vehicle.send(heartbeat(new FrameEncoder(1, 1), 0)));
        }
    }

    @Test
    void aSerialLinkCarriesFramesBothWaysOverAPseudoTerminal() throws IOException {
        try (PseudoTerminal radio = PseudoTerminal.open();
             SerialMavlinkLink gcs = SerialMavlinkLink.open(radio.devicePath(), SerialMavlinkLink.DEFAULT_BAUD)) {
            OutputStream toGcs = radio.masterOutput();
            byte[] hb = heartbeat(new FrameEncoder(1, 1), 15);
            // split across writes, with line noise before it, as a radio delivers it
            toGcs.write(new byte[]{0x00, 0x55, (byte) 0xFE, 0x01});
            toGcs.write(hb, 0, 5);
            toGcs.flush();
            toGcs.write(hb, 5, hb.length - 5);
            toGcs.flush();
            List<Frame> got = receiveOne(gcs, new ArrayList<>());
            assertEquals(15, got.get(0).payload().getLong(Messages.Heartbeat.CUSTOM_MODE));

            assertTrue(gcs.send(heartbeat(new FrameEncoder(255, 190), 3)));
            List<Frame> atVehicle = new ArrayList<>();
            FrameDecoder d = new FrameDecoder(atVehicle::add);
            byte[] buf = new byte[256];
            Await.until("the heartbeat at the radio", WAIT, () -> {
                try {
                    d.feed(buf, 0, Math.max(0, radio.read(buf, 0, buf.length, Duration.ofMillis(200))));
                } catch (IOException e) {
                    throw new UncheckedIOException(e);
                }
                return !atVehicle.isEmpty();
            });
            assertEquals(3, atVehicle.get(0).payload().getLong(Messages.Heartbeat.CUSTOM_MODE));
            assertEquals("serial " + radio.devicePath() + " at 57600 baud", gcs.describe());
        }
    }

    @Test
    void aVanishedRadioIsALostLink() throws IOException {
        PseudoTerminal radio = PseudoTerminal.open();
        try (SerialMavlinkLink gcs = SerialMavlinkLink.open(radio.devicePath(), SerialMavlinkLink.DEFAULT_BAUD)) {
            radio.close();
            assertThrows(LinkLostException.class, () -> gcs.receive(Duration.ofSeconds(2), (f, a) -> { }));
        }
    }

    @Test
    void endpointsParseInMavsdkForms() {
        assertEquals(new MavlinkEndpoint(MavlinkEndpoint.Kind.UDP_LISTEN, "0.0.0.0", 14550, "", 0), MavlinkEndpoint.parse("udpin://0.0.0.0:14550"));
        assertEquals(new MavlinkEndpoint(MavlinkEndpoint.Kind.UDP_SEND, "127.0.0.1", 14551, "", 0), MavlinkEndpoint.parse("udp://127.0.0.1:14551"));
        assertEquals(new MavlinkEndpoint(MavlinkEndpoint.Kind.UDP_SEND, "::1", 14551, "", 0), MavlinkEndpoint.parse("udpout://[::1]:14551"));
        assertEquals(new MavlinkEndpoint(MavlinkEndpoint.Kind.SERIAL, "", 0, "/dev/ttyUSB0", 57600), MavlinkEndpoint.parse("serial:///dev/ttyUSB0"));
        assertEquals(115200, MavlinkEndpoint.parse("serial:///dev/ttyACM0:115200").baud());
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> MavlinkEndpoint.parse("tcp://1.2.3.4:5760"));
        assertTrue(e.getMessage().contains("tcp://1.2.3.4:5760") && e.getMessage().contains("udpin://"), e.getMessage());
    }

    @Test
    void anEndpointNamesItsAddressAndSaysWhetherItStaysOnThisMachine() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> MavlinkEndpoint.parse("udp://:14540"));
        assertTrue(e.getMessage().contains("udpin://127.0.0.1:14540") && e.getMessage().contains("udpin://0.0.0.0:14540"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> MavlinkEndpoint.parse("udpin://:14550"));
        assertTrue(MavlinkEndpoint.parse("udpin://127.0.0.1:14550").local());
        assertTrue(MavlinkEndpoint.parse("udpout://[::1]:14550").local());
        assertTrue(MavlinkEndpoint.parse("serial:///dev/ttyUSB0").local());
        assertFalse(MavlinkEndpoint.parse("udpin://0.0.0.0:14550").local());
        assertFalse(MavlinkEndpoint.parse("udpout://192.0.2.7:14550").local());
        assertTrue(MavlinkEndpoint.parse(io.robomw.platform.mavlink.MavlinkPlatformProvider.DEFAULT_LINK).local(), "the driver's default link stays on loopback");
    }
}
