package io.robomw.agents.messaging;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.Socket;
import java.nio.ByteBuffer;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.locks.LockSupport;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A node's {@link PeerLimits} against raw sockets: subscriptions, topic length and connections are
 * bounded and released; peers that never speak, stop in the middle of a frame or trickle bytes are
 * closed; quiet healthy links stay open through keep-alives.
 */
class PeerLimitsTest {

    private static final Duration WAIT = Duration.ofSeconds(20);
    private final List<AutoCloseable> open = new ArrayList<>();

    @AfterEach
    void closeAll() throws Exception {
        for (int i = open.size() - 1; i >= 0; i--) {
            open.get(i).close();
        }
    }

    private MessagingNode node(String name, PeerLimits limits, boolean bind) {
        MessagingNode.Builder b = MessagingNode.builder(name).settings(MessagingSettings.defaults().withLimits(limits));
        if (bind) {
            b.bind("tcp://127.0.0.1:0");
        }
        MessagingNode n = b.build();
        open.add(n);
        return n;
    }

    private Socket connect(MessagingNode server) throws IOException {
        Socket s = new Socket(InetAddress.getLoopbackAddress(), Address.parse(server.address("tcp")).port());
        open.add(s);
        return s;
    }

    private static byte[] control(FrameKind kind, String topic) {
        Frame f = new Frame(kind, 0, 7, 1, new UUID(7, 1), MessagingNode.nowMicros(), "raw", "", topic, "", 0, new byte[0], false);
        return FrameCodec.encode(f, false);
    }

    private static Frame readFrame(InputStream in) throws Exception {
        FrameStreamReader r = new FrameStreamReader(in, 1 << 20);
        int length = r.next();
        if (length < 0) {
            return null;
        }
        return FrameCodec.decode(r.buffer(), r.offset(), length, 1 << 20);
    }

    /** Reads until the node closes the connection; returns the time that took. */
    private static long untilClosed(Socket s) throws IOException {
        long start = System.nanoTime();
        s.setSoTimeout((int) WAIT.toMillis());
        InputStream in = s.getInputStream();
        byte[] buf = new byte[256];
        try {
            while (in.read(buf) >= 0) {
                // keep-alives and the like
            }
        } catch (java.net.SocketException e) {
            // a reset is a close too
        }
        return (System.nanoTime() - start) / 1_000_000;
    }

    @Test
    void subscriptionsAreBoundedPerPeerAndInAllAndReleasedWhenThePeerCloses() throws IOException {
        MessagingNode server = node("server", PeerLimits.defaults().withMaxSubscriptions(10, 15).withMaxTopicBytes(32), true);
        Socket a = connect(server);
        OutputStream out = a.getOutputStream();
        for (int i = 0; i < 20; i++) {
            out.write(control(FrameKind.SUBSCRIBE, "topic-" + i));
        }
        out.write(control(FrameKind.SUBSCRIBE, "x".repeat(33)));
        out.flush();
        Await.until("10 + 1 subscriptions refused", WAIT, () -> server.stats().dropped(DropReason.LIMIT) == 11);
        assertEquals(10, server.remoteSubscribers().total());

        Socket b = connect(server);
        for (int i = 0; i < 10; i++) {
            b.getOutputStream().write(control(FrameKind.SUBSCRIBE, "other-" + i));
        }
        Await.until("5 more refused: 15 in all", WAIT, () -> server.stats().dropped(DropReason.LIMIT) == 16);
        assertEquals(15, server.remoteSubscribers().total());

        b.getOutputStream().write(control(FrameKind.UNSUBSCRIBE, "other-0"));
        Await.until("an unsubscription releases its topic", WAIT, () -> server.remoteSubscribers().total() == 14);
        a.close();
        b.close();
        Await.until("nothing kept once both closed", WAIT, () -> server.remoteSubscribers().total() == 0);
        assertEquals(0, server.remoteSubscribers().topics(), "topics with no subscriber are forgotten");
        assertEquals(0, server.subscriberCount("topic-0"));
    }

    @Test
    void connectionsBeyondTheLimitAreRefusedWithTheReasonAndSlotsComeBack() throws Exception {
        // The two raw connections below hold the slots and never send a frame: the first-frame timeout (10 s by default)
        // would close them, and free a slot, while a loaded machine is still at the steps below.
        MessagingNode server = node("server", PeerLimits.defaults().withMaxConnections(2)
                .withTimeouts(Duration.ofMinutes(5), Duration.ofMinutes(5)), true);
        server.addMessageListener("ask", null, m -> server.replyMessage(m, "yes", "answer"));
        Socket first = connect(server);
        Socket second = connect(server);
        assertEquals(FrameKind.KEEPALIVE, readFrame(first.getInputStream()).kind(), "an accepted connection hears a keep-alive first");
        readFrame(second.getInputStream());

        Socket third = connect(server);
        Frame refusal = readFrame(third.getInputStream());
        assertEquals(FrameKind.ERROR, refusal.kind());
        assertEquals(new UUID(0, 0), refusal.correlationId());
        String why = (String) new PayloadCodec(null, null).decode(refusal.payloadType(), refusal.payload());
        assertTrue(why.contains("at most 2 connections (maxConnections)"), why);
        Await.until("the refusal is counted", WAIT, () -> server.stats().dropped(DropReason.LIMIT) == 1);

        MessagingNode client = node("client", PeerLimits.defaults(), false);
        // The refusal may overtake the request (then sending fails at once), or come after it (then
        // the reply fails with the node's reason): a node beyond the limit never answers, and the
        // user reads why.
        Await.until("a request fails naming the limit", WAIT, () -> {
            String failure = requestFailure(client, server);
            return failure.contains("refused the connection") && failure.contains("maxConnections");
        });

        first.close();
        Await.until("a slot comes back when a peer leaves", WAIT, () -> {
            try {
                return "yes".equals(client.request("server", server.address("tcp"), null, "ask", "?", "q", Duration.ofSeconds(5)).join().payload());
            } catch (RuntimeException retry) {
                return false;
            }
        });
    }

    private static String requestFailure(MessagingNode client, MessagingNode server) {
        return requestFailure(client, server, "tcp");
    }

    private static String requestFailure(MessagingNode client, MessagingNode server, String scheme) {
        try {
            Object answer = client.request("server", server.address(scheme), null, "ask", "?", "q", Duration.ofSeconds(10)).join().payload();
            throw new AssertionError("a node beyond its connection limit answered: " + answer);
        } catch (MessagingException e) {
            return e.getMessage();
        } catch (java.util.concurrent.CompletionException e) {
            return String.valueOf(e.getCause().getMessage());
        }
    }

    @Test
    void rmiSessionsBeyondTheLimitAreRefusedNamingIt() {
        MessagingNode server = node("server", PeerLimits.defaults().withMaxConnections(1), false);
        server.bind("rmi://127.0.0.1:0/limited");
        server.addMessageListener("ask", null, m -> server.replyMessage(m, "yes", "answer"));
        MessagingNode first = node("first", PeerLimits.defaults(), false);
        assertEquals("yes", first.request("server", server.address("rmi"), null, "ask", "?", "q", Duration.ofSeconds(10)).join().payload());

        MessagingNode second = node("second", PeerLimits.defaults(), false);
        String failure = requestFailure(second, server, "rmi");
        assertTrue(failure.contains("serves at most 1 sessions (maxConnections)"), failure);
        Await.until("the refusal is counted", WAIT, () -> server.stats().dropped(DropReason.LIMIT) == 1);
    }

    @Test
    void peersThatNeverSpeakStopMidFrameOrTrickleAreClosedAfterTheirTimeouts() throws Exception {
        MessagingNode server = node("server", PeerLimits.defaults().withTimeouts(Duration.ofMillis(800), Duration.ofMillis(1200)), true);

        Socket silent = connect(server);
        long silentMillis = untilClosed(silent);
        assertTrue(silentMillis >= 700, "closed after " + silentMillis + " ms, before the first-frame timeout");

        Socket half = connect(server);
        half.getOutputStream().write(control(FrameKind.SUBSCRIBE, "ok"));
        byte[] next = control(FrameKind.SUBSCRIBE, "never finished");
        half.getOutputStream().write(next, 0, next.length / 2);
        long halfMillis = untilClosed(half);
        assertTrue(halfMillis >= 1000, "closed after " + halfMillis + " ms, before the idle timeout");

        Socket trickle = connect(server);
        byte[] frame = control(FrameKind.SUBSCRIBE, "x".repeat(200));
        Thread dripper = new Thread(() -> {
            try {
                for (byte b : frame) {
                    trickle.getOutputStream().write(b);
                    LockSupport.parkNanos(50_000_000); // the peer under test sends a byte every 50 ms
                }
            } catch (IOException closed) {
                // the node closed it: what this test wants
            }
        }, "trickling-peer");
        dripper.start();
        untilClosed(trickle);
        dripper.join(WAIT.toMillis());
        assertEquals(0, server.subscriberCount("x".repeat(200)), "the trickled frame never completed");
        Await.until("three connections timed out", WAIT, () -> server.stats().dropped(DropReason.TIMED_OUT) == 3);
        Await.until("the half-sent peer's subscription went with it", WAIT, () -> server.remoteSubscribers().total() == 0);
    }

    @Test
    void aListenerSlowerThanTheIdleTimeoutIsNotThePeersSilence() throws Exception {
        MessagingNode server = node("server", PeerLimits.defaults().withTimeouts(Duration.ofMillis(600), Duration.ofMillis(600)), true);
        server.addMessageListener("slow", null, m -> LockSupport.parkNanos(Duration.ofMillis(1500).toNanos())); // slow work, not a wait
        Socket peer = connect(server);
        Frame request = new Frame(FrameKind.MESSAGE, 0, 7, 1, new UUID(7, 1), MessagingNode.nowMicros(), "raw", "server", "slow", "",
                PayloadCodec.NULL, new byte[0], false);
        long start = System.nanoTime();
        peer.getOutputStream().write(FrameCodec.encode(request, false));
        untilClosed(peer);
        long millis = (System.nanoTime() - start) / 1_000_000;
        // silent after its one frame: closed one idle timeout after the listener was done, not during it
        assertTrue(millis >= 1500 + 500, "closed after " + millis + " ms, while its frame was still being handled");
        Await.until("the silent peer timed out", WAIT, () -> server.stats().dropped(DropReason.TIMED_OUT) == 1);
    }

    @Test
    void quietHealthyLinksAreKeptOpenByKeepAlives() {
        PeerLimits quick = PeerLimits.defaults().withTimeouts(Duration.ofMillis(1500), Duration.ofMillis(1500));
        MessagingNode server = node("server", quick, true);
        List<Object> got = new CopyOnWriteArrayList<>();
        MessagingNode client = node("client", quick, false);
        client.addMessageListener("news", null, m -> got.add(m.payload()));
        client.subscribeMessage("news", null);
        client.connect(server.address("tcp"));
        Await.until("the client subscribed", WAIT, () -> server.subscriberCount("news") == 1);

        // Nothing but keep-alives for three idle timeouts: the link must stay up all along.
        long end = System.nanoTime() + Duration.ofMillis(4500).toNanos();
        while (System.nanoTime() < end) {
            assertEquals(1, server.subscriberCount("news"), "the quiet link was cut");
            LockSupport.parkNanos(20_000_000);
        }
        assertEquals(0, server.stats().dropped(DropReason.TIMED_OUT));
        assertEquals(0, client.stats().dropped(DropReason.TIMED_OUT));
        server.publishMessage("news", "still here", "text", null);
        Await.until("a publication still arrives", WAIT, () -> got.contains("still here"));
    }
}
