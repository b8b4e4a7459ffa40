package io.robomw.agents.messaging;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.FrameMac;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.security.TopicKeys;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

import javax.crypto.SecretKey;
import java.io.IOException;
import java.io.OutputStream;
import java.net.DatagramPacket;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.Arrays;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * Truncated, oversized, garbage, replayed and stale frames sent with raw sockets: each is dropped
 * with a counter, and the node keeps serving a well-behaved peer.
 */
class BadInputTest {

    private static final Duration WAIT = Duration.ofSeconds(10);
    private MessagingNode server;
    private final List<Object> got = new CopyOnWriteArrayList<>();
    private final SecretKey key = new TopicKeys().key("cmd", "pw");

    /** Each test's own: its hand-made frames come from one fixed source, which a window kept across tests would take for replays. */
    @org.junit.jupiter.api.io.TempDir
    java.nio.file.Path replays;

    @BeforeEach
    void startServer() {
        server = MessagingNode.builder("server").settings(MessagingSettings.defaults().withMaxFrameSize(64 * 1024)).replayDirectory(replays)
                .bind("tcp://127.0.0.1:0").bind("udp://127.0.0.1:0").build();
        server.addMessageListener("cmd", "pw", m -> got.add(m.payload()));
    }

    @AfterEach
    void stopServer() {
        server.close();
    }

    private static byte[] frame(String payload, long number, long timestampMicros, SecretKey key) {
        PayloadCodec.Encoded p = new PayloadCodec(null, null).encode(payload);
        Frame f = new Frame(FrameKind.MESSAGE, 1, 42, number, new UUID(42, number), timestampMicros, "raw", "server", "cmd", "go",
                p.type(), p.bytes(), key != null);
        byte[] bytes = FrameCodec.encode(f, key != null);
        if (key != null) {
            new FrameMac().sign(key, bytes);
        }
        return bytes;
    }

    private byte[] good(String payload, long number) {
        return frame(payload, number, MessagingNode.nowMicros(), key);
    }

    private int port(String scheme) {
        return Address.parse(server.address(scheme)).port();
    }

    private void sendTcp(byte[]... chunks) throws IOException {
        try (Socket s = new Socket(InetAddress.getLoopbackAddress(), port("tcp"))) {
            OutputStream out = s.getOutputStream();
            for (byte[] c : chunks) {
                out.write(c);
            }
            out.flush();
            s.shutdownOutput();
            s.getInputStream().readAllBytes();
        }
    }

    private void sendUdp(byte[] datagram) throws IOException {
        try (DatagramSocket s = new DatagramSocket(0, InetAddress.getLoopbackAddress())) {
            s.send(new DatagramPacket(datagram, datagram.length, InetAddress.getLoopbackAddress(), port("udp")));
        }
    }

    private void assertDroppedThenStillServing(DropReason reason, long number) throws IOException {
        Await.until(reason + " counted", WAIT, () -> server.stats().dropped(reason) == 1);
        sendTcp(good("after", number));
        Await.until("a good frame is still delivered", WAIT, () -> got.contains("after"));
    }

    @Test
    void garbageOnAConnectionIsDroppedAndTheNodeKeepsServing() throws IOException {
        sendTcp("GET / HTTP/1.1\r\nHost: x\r\n\r\n".getBytes(StandardCharsets.US_ASCII));
        assertDroppedThenStillServing(DropReason.MALFORMED, 1);
    }

    @Test
    void anErrorThrownByAListenerIsCountedAndTheConnectionGoesOn() throws IOException {
        server.addMessageListener("cmd", "pw", m -> {
            if ("boom".equals(m.payload())) {
                throw new AssertionError("a listener's own bug"); // an error, not an exception: agent code can throw one
            }
        });
        sendTcp(good("boom", 1), good("after", 2));
        Await.until("the message after the failing one is delivered on the same connection", WAIT, () -> got.contains("after"));
        assertEquals(List.of("boom", "after"), got);
    }

    @Test
    void oversizedFrameIsDroppedAndTheNodeKeepsServing() throws IOException {
        byte[] huge = good("x", 1);
        java.nio.ByteBuffer.wrap(huge).putInt(FrameCodec.FRAME_LENGTH_OFFSET, 10_000_000);
        sendTcp(huge);
        assertDroppedThenStillServing(DropReason.OVERSIZED, 2);
    }

    @Test
    void truncatedFrameIsDroppedAndTheNodeKeepsServing() throws IOException {
        byte[] f = good("x", 1);
        sendTcp(Arrays.copyOf(f, f.length - 10));
        assertDroppedThenStillServing(DropReason.TRUNCATED, 2);
    }

    @Test
    void replayedFrameIsDroppedOnce() throws IOException {
        byte[] f = good("once", 7);
        sendTcp(f, f);
        Await.until("replay counted", WAIT, () -> server.stats().dropped(DropReason.REPLAYED) == 1);
        assertEquals(List.of("once"), got);
        sendTcp(f);
        Await.until("replay on a new connection counted", WAIT, () -> server.stats().dropped(DropReason.REPLAYED) == 2);
        assertEquals(List.of("once"), got);
    }

    @Test
    void staleFrameIsDropped() throws IOException {
        sendTcp(frame("old", 3, MessagingNode.nowMicros() - 3_600_000_000L, key));
        assertDroppedThenStillServing(DropReason.STALE, 4);
        assertEquals(List.of("after"), got);
    }

    @Test
    void garbageAndTruncatedDatagramsAreDroppedAndTheSocketKeepsServing() throws IOException {
        sendUdp("hello?".getBytes(StandardCharsets.US_ASCII));
        byte[] f = good("x", 1);
        sendUdp(Arrays.copyOf(f, f.length - 5));
        byte[] junk = new byte[200];
        new java.util.Random(1).nextBytes(junk);
        sendUdp(junk);
        Await.until("three bad datagrams counted", WAIT, () -> server.stats().dropped(DropReason.TRUNCATED) == 2
                && server.stats().dropped(DropReason.MALFORMED) == 1);
        sendUdp(good("udp-after", 2));
        Await.until("a good datagram is still delivered", WAIT, () -> got.contains("udp-after"));
    }

    @Test
    void gapsInADatagramStreamAreCountedAsLost() throws IOException {
        for (long seq : new long[] {1, 2, 5, 6}) {
            byte[] f = good("n" + seq, 100 + seq);
            FrameCodec.writeStreamSequence(f, 0, seq);
            try (DatagramSocket s = new DatagramSocket(0, InetAddress.getLoopbackAddress())) {
                s.send(new DatagramPacket(f, f.length, InetAddress.getLoopbackAddress(), port("udp")));
            }
        }
        Await.until("four datagrams arrive", WAIT, () -> got.size() == 4);
        assertEquals(0, server.stats().framesLost(), "each datagram came from its own socket: four streams, no gap");
    }
}
