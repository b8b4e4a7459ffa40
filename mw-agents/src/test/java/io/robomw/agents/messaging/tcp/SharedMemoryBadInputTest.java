package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.shm.Handshake;
import io.robomw.agents.messaging.shm.SharedReference;
import io.robomw.agents.messaging.shm.SharedSegment;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A subscriber node against a hand-driven publisher on a real socket: references that do not hold
 * (no offer accepted, outside the segment, out of order) end that connection only, counted as
 * {@link DropReason#MALFORMED}; an offer of a file that is not a segment is not accepted and the
 * publications go on over TCP.
 */
class SharedMemoryBadInputTest {

    private static final Duration WAIT = Duration.ofSeconds(30);
    private final List<AutoCloseable> open = new ArrayList<>();
    private final List<Object> got = new CopyOnWriteArrayList<>();
    private MessagingNode sub;
    private Socket socket;
    private FrameStreamReader in;
    private OutputStream out;

    @AfterEach
    void close() throws Exception {
        for (int i = open.size() - 1; i >= 0; i--) {
            open.get(i).close();
        }
    }

    /** Connects a subscriber node to a socket this test drives, and reads until it asked for shared memory. */
    private void connect() throws Exception {
        ServerSocket server = new ServerSocket(0, 4, InetAddress.getLoopbackAddress());
        open.add(server);
        sub = MessagingNode.builder("sub").settings(MessagingSettings.defaults()).replayDirectory(null)
                .connect("tcp://127.0.0.1:" + server.getLocalPort()).build();
        open.add(sub);
        sub.addMessageListener("scan", null, m -> got.add(m.payload()));
        sub.subscribeMessage("scan", null);
        server.setSoTimeout((int) WAIT.toMillis());
        socket = server.accept();
        open.add(socket);
        socket.setSoTimeout((int) WAIT.toMillis());
        in = new FrameStreamReader(socket.getInputStream(), 1 << 20);
        out = socket.getOutputStream();
        next(FrameKind.SHM_ASK);
    }

    /** @return the next frame of that kind the node sent (others are skipped) */
    private Frame next(FrameKind kind) throws Exception {
        while (true) {
            int length = in.next();
            assertTrue(length > 0, "the node closed the connection while the test waited for " + kind);
            Frame f = FrameCodec.decode(in.buffer(), in.offset(), length, 1 << 20);
            if (f.kind() == kind) {
                return f;
            }
        }
    }

    private static byte[] publication(byte[] payload) {
        return FrameCodec.encode(new Frame(FrameKind.PUBLISH, 0, 7, 1, new UUID(7, 1), FrameFactoryTime.now(), "pub", "", "scan", "data",
                PayloadCodec.BYTES, payload, false), false);
    }

    /** Makes a segment, offers it and reads the acceptance. */
    private SharedSegment.Subscriber offer(SharedSegment segment) throws Exception {
        SharedSegment.Subscriber cell = segment.attach(() -> { });
        out.write(Handshake.offer(new Handshake.Offer(cell.cell(), segment.nonce(), segment.file())));
        Handshake.Accept accept = Handshake.readAccept(next(FrameKind.SHM_ACCEPT)).orElseThrow();
        assertEquals(cell.cell(), accept.cell());
        cell.activate();
        return cell;
    }

    private void assertConnectionEndsWithMalformed() {
        Await.until("the node ends the connection", WAIT, () -> {
            try {
                return in.next() < 0;
            } catch (Exception e) {
                return true;
            }
        });
        Await.until("a MALFORMED drop is counted", WAIT, () -> sub.stats().dropped(DropReason.MALFORMED) >= 1);
    }

    @Test
    void aReferenceWithoutAnAcceptedOfferEndsTheConnection() throws Exception {
        connect();
        out.write(SharedReference.frameFor(publication(new byte[100_000]), 1, 0));
        assertConnectionEndsWithMalformed();
        assertEquals(List.of(), got);
    }

    @Test
    void aReferenceOutsideTheSegmentEndsTheConnectionAfterTheGoodOnesCame() throws Exception {
        connect();
        SharedSegment segment = SharedSegment.create(SharedSegment.DIRECTORY, 1 << 20, 4);
        open.add(segment);
        SharedSegment.Subscriber cell = offer(segment);
        byte[] payload = new byte[100_000];
        new java.util.Random(3).nextBytes(payload);
        segment.send(publication(payload), cell, out::write, WAIT.toNanos());
        Await.until("the good one arrives", WAIT, () -> got.size() == 1);
        assertArrayEquals(payload, (byte[]) got.get(0));
        out.write(SharedReference.frameFor(publication(new byte[100_000]), 2, (1 << 20) - 64));
        assertConnectionEndsWithMalformed();
        assertEquals(1, got.size());
    }

    @Test
    void aReferenceOutOfOrderEndsTheConnection() throws Exception {
        connect();
        SharedSegment segment = SharedSegment.create(SharedSegment.DIRECTORY, 1 << 20, 4);
        open.add(segment);
        SharedSegment.Subscriber cell = offer(segment);
        List<byte[]> refs = new ArrayList<>();
        segment.send(publication(new byte[70_000]), cell, refs::add, WAIT.toNanos());
        segment.send(publication(new byte[70_000]), cell, refs::add, WAIT.toNanos());
        out.write(refs.get(1));
        out.write(refs.get(0));
        assertConnectionEndsWithMalformed();
        assertEquals(1, got.size());
    }

    @Test
    void anOfferOfAFileThatIsNotASegmentIsNotAcceptedAndPublicationsGoOnOverTcp() throws Exception {
        connect();
        out.write(Handshake.offer(new Handshake.Offer(0, 42, java.nio.file.Path.of("/etc/passwd"))));
        out.write(Handshake.offer(new Handshake.Offer(0, 42, SharedSegment.DIRECTORY.resolve("robomw-shm-1-none.seg"))));
        byte[] payload = new byte[100_000];
        out.write(publication(payload));
        Await.until("the publication arrives over TCP", WAIT, () -> got.size() == 1);
        assertArrayEquals(payload, (byte[]) got.get(0));
        assertEquals(0, sub.stats().droppedTotal(), "a refused offer is not a dropped frame");
    }

    /** Frames carry a timestamp; the test's publications are fresh. */
    private static final class FrameFactoryTime {
        static long now() {
            java.time.Instant t = java.time.Instant.now();
            return t.getEpochSecond() * 1_000_000L + t.getNano() / 1000;
        }
    }
}
