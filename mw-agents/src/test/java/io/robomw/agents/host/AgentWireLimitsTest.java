package io.robomw.agents.host;

import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.OutputStream;
import java.net.Socket;
import java.net.SocketException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.SecureRandom;
import java.time.Duration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * What a host's agent wire does with frames that break its rules (docs/agents.md, "Trust"; the
 * table in {@link WireFrames}): each is refused with a reason naming the peer and what was wrong,
 * counted, and its connection closed, and the host goes on serving; a peer that has not proved its
 * session on a connection cannot make the host read a large frame; a connection that sends no
 * verified first frame in time is closed; connections beyond the limit are closed at once. The
 * frames are written byte by byte on real loopback sockets.
 */
class AgentWireLimitsTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("agent wire limits");
    private AgentHost host;
    private Session session;
    private long seq = 1;

    @BeforeEach
    void start() throws Exception {
        host = AgentHost.builder("guarded").clusterKey(KEY).noMessaging()
                .wireLimits(new WireServer.Limits(3, Duration.ofSeconds(5), Duration.ofMinutes(2), Duration.ofSeconds(10), 1 << 20)).start();
        session = link("tester").sessionForTests();
    }

    @AfterEach
    void close() {
        host.close();
    }

    private PeerLink link(String name) {
        return new PeerLink(HostAddress.parse(host.address()), name, KEY, new HostSockets.Client("127.0.0.1", false, 10_000), new SecureRandom());
    }

    /** A test's end of a wire connection, writing whatever frames a test makes. */
    private final class Raw implements AutoCloseable {
        final Socket socket = new Socket("127.0.0.1", host.wirePort());
        final OutputStream out;
        final DataInputStream in;

        Raw() throws IOException {
            socket.setSoTimeout(10_000);
            out = socket.getOutputStream();
            in = new DataInputStream(socket.getInputStream());
        }

        /** Writes a frame: the header as given, the body, and the right tag under {@code s} or a wrong one. */
        void send(int version, int code, Session s, long n, long claimedLength, byte[] body, boolean rightTag) throws IOException {
            byte[] header = ByteBuffer.allocate(WireFrames.HEADER).put((byte) version).put((byte) code).putLong(s.id).putLong(n)
                    .putInt((int) claimedLength).array();
            FrameTag tag = new FrameTag();
            tag.start(s.frameKey, WireFrames.DIRECTION_REQUEST, n, false);
            tag.update(header, 0, header.length);
            tag.update(body, 0, body.length);
            byte[] t = tag.finish().clone();
            if (!rightTag) {
                t[0] ^= 1;
            }
            out.write(header);
            out.write(body);
            if (claimedLength == body.length) {
                out.write(t);
            }
            out.flush();
        }

        void hello(long n) throws IOException {
            send(WireFrames.VERSION, WireFrames.OP_HELLO, session, n, 0, new byte[0], true);
        }

        /** @return the next answer's status code and body, or {@code null} if the host closed the connection instead */
        Answer answer() throws IOException {
            byte[] header = new byte[WireFrames.HEADER];
            try {
                in.readFully(header);
            } catch (EOFException | SocketException closed) {
                return null;
            }
            WireFrames.Header h = WireFrames.Header.read(header, 0);
            byte[] body = new byte[(int) h.length()];
            in.readFully(body);
            in.readFully(new byte[WireFrames.TAG]);
            return new Answer(h.code(), new String(body, StandardCharsets.UTF_8));
        }

        /** @return whether the host has closed the connection (nothing more to read) */
        boolean closedByHost() throws IOException {
            try {
                return in.read() < 0;
            } catch (SocketException reset) {
                return true;
            }
        }

        String local() {
            return "127.0.0.1:" + socket.getLocalPort();
        }

        @Override
        public void close() throws IOException {
            socket.close();
        }
    }

    private record Answer(int code, String text) {
    }

    /** Sends what {@code frames} writes on a fresh connection and checks the refusal: its reason, the peer named, the connection closed. */
    private void refused(String expected, boolean proved, FrameWriter frames) throws IOException {
        long before = host.refused();
        try (Raw raw = new Raw()) {
            if (proved) {
                raw.hello(seq++);
                assertEquals(Reply.Status.OK.code(), raw.answer().code());
            }
            frames.write(raw);
            Answer a = raw.answer();
            assertEquals(WireFrames.STATUS_FRAME_REFUSED, a.code(), () -> "refused: " + a);
            assertTrue(a.text().contains(expected), a.text());
            assertTrue(a.text().contains("host guarded refused an agent wire frame from") && a.text().contains(raw.local()),
                    "names the peer: " + a.text());
            assertTrue(raw.closedByHost(), "the connection is closed after " + expected);
        }
        assertEquals(before + 1, host.refused(), "counted once");
        servesStill();
    }

    @FunctionalInterface
    private interface FrameWriter {
        void write(Raw raw) throws IOException;
    }

    /** The host serves a new connection and a new peer after a refusal. */
    private void servesStill() throws IOException {
        try (Raw raw = new Raw()) {
            raw.hello(seq++);
            assertEquals(Reply.Status.OK.code(), raw.answer().code());
        }
        assertEquals(Reply.Status.OK, link("after").call(Op.LIST, new byte[0]).status());
    }

    @Test
    void malformedFramesAreRefusedNamingThePeerAndTheHostKeepsServing() throws Exception {
        refused("unknown agent wire protocol version 9", false, raw -> raw.send(9, WireFrames.OP_HELLO, session, seq++, 0, new byte[0], true));
        refused("wrong tag", false, raw -> raw.send(WireFrames.VERSION, WireFrames.OP_HELLO, session, seq++, 0, new byte[0], false));
        refused("must be HELLO", false, raw -> raw.send(WireFrames.VERSION, Op.TRANSFER.code(), session, seq++, 3, new byte[3], true));
        refused("ended within a frame, after", false, raw -> {
            raw.send(WireFrames.VERSION, WireFrames.OP_HELLO, session, seq++, 100, new byte[10], true);
            raw.socket.shutdownOutput();
        });
        refused("ended within a frame's header, after 5 of its 22 bytes", false, raw -> {
            raw.out.write(new byte[] {3, 64, 0, 0, 0});
            raw.socket.shutdownOutput();
        });
        refused("at most 1048576 are read", true,
                raw -> raw.send(WireFrames.VERSION, Op.TRANSFER.code(), session, seq++, 0xFFFF_FFF0L, new byte[0], true));
        Session other = link("other").sessionForTests();
        refused("on a connection of another session", true, raw -> raw.send(WireFrames.VERSION, WireFrames.OP_HELLO, other, 1, 0, new byte[0], true));
    }

    @Test
    void aPeerThatHasNotProvedItsSessionOnTheConnectionCannotMakeTheHostReadALargeFrame() throws Exception {
        refused("a frame announces a body of 1048576 bytes; at most " + (HostEndpoint.UNPROVEN_MAX_BYTES - WireFrames.HEADER - WireFrames.TAG)
                + " are read before a frame on the connection has verified", false,
                raw -> raw.send(WireFrames.VERSION, WireFrames.OP_HELLO, session, seq++, 1 << 20, new byte[0], true));
    }

    @Test
    void replayedAndReorderedFramesAreRefused() throws Exception {
        long served = seq++;
        refused("sequence number " + served + " is not above the connection's last, " + served + " (replayed or reordered)", false, raw -> {
            raw.hello(served);
            assertEquals(Reply.Status.OK.code(), raw.answer().code());
            raw.hello(served);
        });
        refused("sequence number " + served + " was served before on its session (replayed)", false, raw -> raw.hello(served));
        long later = seq + 10;
        refused("sequence number " + (later - 1) + " is not above the connection's last, " + later, false, raw -> {
            raw.hello(later);
            assertEquals(Reply.Status.OK.code(), raw.answer().code());
            raw.hello(later - 1);
        });
        seq = later + 1;
    }

    @Test
    void anUnknownOperationIsRefusedUnderTheTagAndTheConnectionKept() throws Exception {
        try (Raw raw = new Raw()) {
            raw.hello(seq++);
            assertEquals(Reply.Status.OK.code(), raw.answer().code());
            raw.send(WireFrames.VERSION, 99, session, seq++, 0, new byte[0], true);
            Answer a = raw.answer();
            assertEquals(Reply.Status.REFUSED.code(), a.code());
            assertTrue(a.text().contains("unknown operation code 99"), a.text());
            raw.hello(seq++);
            assertEquals(Reply.Status.OK.code(), raw.answer().code(), "the connection still serves");
        }
    }

    @Test
    void aFrameOfASessionTheHostDoesNotKnowIsAnsweredUnknownSession() throws Exception {
        Session forged = new Session(session.id + 1, new byte[32]);
        try (Raw raw = new Raw()) {
            raw.send(WireFrames.VERSION, WireFrames.OP_HELLO, forged, 1, 0, new byte[0], true);
            assertEquals(Reply.Status.UNKNOWN_SESSION.code(), raw.answer().code());
            assertTrue(raw.closedByHost());
        }
        servesStill();
    }

    @Test
    void aConnectionWithoutAVerifiedFirstFrameInTimeIsClosed() throws Exception {
        try (Raw raw = new Raw()) {
            Answer a = raw.answer();
            assertEquals(WireFrames.STATUS_FRAME_REFUSED, a.code());
            assertTrue(a.text().contains("no verified first frame within 5000 ms of connecting") && a.text().contains(raw.local()), a.text());
            assertTrue(raw.closedByHost());
        }
        servesStill();
    }

    @Test
    void connectionsOverTheLimitAreClosedAtOnce() throws Exception {
        // each connection says hello as soon as it is open: the first-frame deadline runs from the accept
        Raw[] open = new Raw[3];
        try {
            for (int i = 0; i < open.length; i++) {
                open[i] = new Raw();
                open[i].hello(seq++);
                assertEquals(Reply.Status.OK.code(), open[i].answer().code());
            }
            try (Raw fourth = new Raw()) {
                assertNull(fourth.answer(), "closed without an answer");
            }
            open[0].close();
            Await.until("the host counts the closed connection", Duration.ofSeconds(10), () -> host.wireConnections() == 2);
            try (Raw again = new Raw()) {
                again.hello(seq++);
                assertEquals(Reply.Status.OK.code(), again.answer().code());
            }
        } finally {
            for (Raw r : open) {
                if (r != null) {
                    r.close();
                }
            }
        }
    }
}
