package io.robomw.agents.messaging;

import io.robomw.testkit.Await;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Set;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.Supplier;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Without a reply spin, a thread waiting for a reply over plain TCP reads the link itself while no
 * other thread does (leader/follower: {@code TcpConnection}, {@code ReadLeadership}). What a user
 * relies on must hold whoever reads: every caller gets its own reply, frames for listeners are
 * delivered in order on the link's reader thread, nothing is lost when a reading caller stops,
 * and closing, interrupts and timeouts end a reading caller's wait. Real sockets on loopback.
 *
 * <p>Whether a caller is reading the link is seen from its stack (the method that does it), since
 * that is the one state the tests must reach before they go on: a waiting thread leads once a
 * frame has passed the reader thread, which the tests cause by sending one (a subscription or a
 * keep-alive).
 */
class CallerReadsReplyTest {

    private static final Duration WAIT = Duration.ofSeconds(20);
    private static final MessagingSettings NO_SPIN = MessagingSettings.defaults().withReplySpin(Duration.ZERO);

    private final List<AutoCloseable> open = new CopyOnWriteArrayList<>();
    private final List<Thread> threads = new CopyOnWriteArrayList<>();

    @AfterEach
    void closeAll() throws Exception {
        for (int i = open.size() - 1; i >= 0; i--) {
            open.get(i).close();
        }
        for (Thread t : threads) {
            t.interrupt();
            t.join(WAIT.toMillis());
        }
    }

    private MessagingNode node(String name, MessagingSettings settings, boolean bind) {
        MessagingNode.Builder b = MessagingNode.builder(name).settings(settings);
        if (bind) {
            b.bind("tcp://127.0.0.1:0");
        }
        MessagingNode n = b.build();
        open.add(n);
        return n;
    }

    /** Runs {@code work} on a thread of its own; the future holds its result or what it threw. */
    private <T> CompletableFuture<T> onThread(String name, Supplier<T> work, List<Thread> into) {
        CompletableFuture<T> result = new CompletableFuture<>();
        Thread t = new Thread(() -> {
            try {
                result.complete(work.get());
            } catch (Throwable e) {
                result.completeExceptionally(e);
            }
        }, name);
        threads.add(t);
        into.add(t);
        t.start();
        return result;
    }

    private static boolean onStack(Thread t, String method) {
        return Arrays.stream(t.getStackTrace()).anyMatch(e -> e.getClassName().endsWith(".TcpConnection") && e.getMethodName().equals(method));
    }

    /** @return whether {@code t} is reading a link for its wait */
    private static boolean leads(Thread t) {
        return onStack(t, "leadAsCaller");
    }

    private static Throwable failure(CompletableFuture<?> f) throws Exception {
        try {
            f.get(WAIT.toMillis(), TimeUnit.MILLISECONDS);
            return null;
        } catch (java.util.concurrent.ExecutionException e) {
            return e.getCause();
        }
    }

    @Test
    void concurrentCallersOnOneLinkEachGetTheirOwnReply() throws Exception {
        MessagingNode server = node("server", NO_SPIN, true);
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", NO_SPIN, false);
        String host = server.address("tcp");
        int callers = 6;
        int each = 300;
        List<CompletableFuture<Integer>> done = new ArrayList<>();
        List<Thread> started = new ArrayList<>();
        for (int c = 0; c < callers; c++) {
            int caller = c;
            done.add(onThread("caller-" + c, () -> {
                for (int i = 0; i < each; i++) {
                    String sent = caller + ":" + i;
                    UUID id = client.sendMessage("server", host, null, "echo", sent, "say");
                    Message reply = client.waitForReply(id, WAIT);
                    assertEquals(sent, reply.payload(), "caller " + caller + " got another caller's reply");
                    assertEquals(id, reply.correlationId());
                }
                return each;
            }, started));
        }
        for (CompletableFuture<Integer> f : done) {
            assertEquals(each, f.get(WAIT.toMillis() * 3, TimeUnit.MILLISECONDS));
        }
        assertEquals(0, client.stats().droppedTotal(), "no reply was unsolicited, refused or lost");
        assertEquals(callers * each, client.stats().framesIn(), "every reply arrived once");
    }

    @Test
    void aReplyArrivingWhileAnotherThreadLeadsReachesItsOwnCaller() throws Exception {
        MessagingNode server = node("server", NO_SPIN, true);
        BlockingQueue<Message> held = new LinkedBlockingQueue<>();
        server.addMessageListener("slow", null, held::add);
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", NO_SPIN, false);
        String host = server.address("tcp");
        UUID slow = client.sendMessage("server", host, null, "slow", "a", "say");
        List<Thread> a = new ArrayList<>();
        CompletableFuture<Message> first = onThread("caller-a", () -> client.waitForReply(slow, WAIT), a);
        Message request = held.poll(WAIT.toMillis(), TimeUnit.MILLISECONDS);
        AtomicInteger nudges = new AtomicInteger();
        Await.until("caller a reads the link itself", WAIT, () -> {
            server.subscribeMessage("nudge-" + nudges.incrementAndGet(), null); // a frame for the reader thread to pass on
            return leads(a.get(0));
        });
        for (int i = 0; i < 20; i++) {
            UUID id = client.sendMessage("server", host, null, "echo", "b" + i, "say");
            assertEquals("b" + i, client.waitForReply(id, WAIT).payload(), "a reply read by caller a reaches this caller");
            assertTrue(leads(a.get(0)), "caller a still reads the link");
            assertFalse(first.isDone(), "caller a still waits for its own reply");
        }
        server.replyMessage(request, "a done", "ok");
        assertEquals("a done", first.get(WAIT.toMillis(), TimeUnit.MILLISECONDS).payload());
        Await.until("the client saw every subscription", WAIT, () -> client.subscriberCount("nudge-" + nudges.get()) == 1);
    }

    @Test
    void aCallerThatTimesOutWhileReadingLeavesAHalfReadFrameToTheNextReader() throws Exception {
        try (ServerSocket raw = new ServerSocket(0, 50, InetAddress.getLoopbackAddress())) {
            MessagingNode client = node("client", NO_SPIN, false);
            String host = "tcp://127.0.0.1:" + raw.getLocalPort();
            List<Object> news = new CopyOnWriteArrayList<>();
            client.addMessageListener("news", null, m -> news.add(m.payload()));
            client.subscribeMessage("news", null);
            UUID slow = client.sendMessage("raw", host, null, "slow", "a", "say");
            Socket peer = raw.accept();
            open.add(peer);
            peer.setSoTimeout((int) WAIT.toMillis());
            FrameStreamReader in = new FrameStreamReader(peer.getInputStream(), 1 << 20);
            OutputStream out = peer.getOutputStream();
            assertEquals(slow, nextRequest(in).correlationId());
            CompletableFuture<Message> other = client.request("raw", host, null, "other", "b", "say", WAIT);
            Frame requestB = nextRequest(in);

            List<Thread> a = new ArrayList<>();
            CompletableFuture<Message> first = onThread("caller-a", () -> client.waitForReply(slow, Duration.ofSeconds(3)), a);
            Await.until("caller a reads the link itself", WAIT, () -> {
                write(out, frame(FrameKind.KEEPALIVE, new UUID(0, 0), "", "", PayloadCodec.NULL, new byte[0]));
                return leads(a.get(0));
            });
            byte[] payload = new byte[200_000];
            new java.util.Random(7).nextBytes(payload);
            byte[] reply = frame(FrameKind.REPLY, requestB.correlationId(), requestB.sender(), "other", PayloadCodec.BYTES, payload);
            int half = reply.length / 2;
            out.write(reply, 0, half);
            out.flush();

            Throwable timedOut = failure(first);
            assertInstanceOf(MessagingException.class, timedOut);
            assertTrue(timedOut.getMessage().contains("no reply"), timedOut.getMessage());
            assertFalse(other.isDone(), "half a frame is no reply");
            out.write(reply, half, reply.length - half);
            out.flush();
            assertArrayEquals(payload, (byte[]) other.get(WAIT.toMillis(), TimeUnit.MILLISECONDS).payload(),
                    "the frame caller a had half read arrives whole");
            for (int i = 0; i < 100; i++) {
                write(out, frame(FrameKind.PUBLISH, new UUID(99, 1000 + i), "", "news", PayloadCodec.STRING,
                        ("n" + i).getBytes(StandardCharsets.UTF_8)));
            }
            Await.until("100 publications after it", WAIT, () -> news.size() == 100);
            for (int i = 0; i < 100; i++) {
                assertEquals("n" + i, news.get(i));
            }
            assertEquals(0, client.stats().droppedTotal());
        }
    }

    @Test
    void publicationsAndSubscriptionsArrivingWhileCallersReadAreDeliveredInOrderOnTheReaderThread() throws Exception {
        MessagingNode server = node("server", NO_SPIN, true);
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", NO_SPIN, false);
        List<Object> got = new CopyOnWriteArrayList<>();
        Set<String> deliveredOn = ConcurrentHashMap.newKeySet();
        client.addMessageListener("numbers", null, m -> {
            got.add(m.payload());
            deliveredOn.add(Thread.currentThread().getName());
        });
        client.subscribeMessage("numbers", null);
        String host = server.address("tcp");
        client.connect(host);
        Await.until("the server sees the subscription", WAIT, () -> server.subscriberCount("numbers") == 1);

        AtomicBoolean stop = new AtomicBoolean();
        AtomicInteger roundTrips = new AtomicInteger();
        List<Thread> callers = new ArrayList<>();
        List<CompletableFuture<Integer>> done = new ArrayList<>();
        for (int c = 0; c < 2; c++) {
            int caller = c;
            done.add(onThread("caller-" + c, () -> {
                while (!stop.get()) {
                    String sent = caller + ":" + roundTrips.get();
                    UUID id = client.sendMessage("server", host, null, "echo", sent, "say");
                    assertEquals(sent, client.waitForReply(id, WAIT).payload());
                    roundTrips.incrementAndGet();
                }
                return 0;
            }, callers));
        }
        Await.until("callers under way", WAIT, () -> roundTrips.get() > 50);
        int n = 3000;
        for (int i = 0; i < n; i++) {
            server.publishMessage("numbers", i, "n", null);
            if (i == n / 2) {
                server.subscribeMessage("status", null);
            }
        }
        Await.until(n + " publications", WAIT, () -> got.size() == n);
        Await.until("the server's subscription, sent among them", WAIT, () -> client.subscriberCount("status") == 1);
        stop.set(true);
        for (CompletableFuture<Integer> f : done) {
            assertEquals(0, f.get(WAIT.toMillis(), TimeUnit.MILLISECONDS));
        }
        for (int i = 0; i < n; i++) {
            assertEquals(i, got.get(i), "publication " + i + " out of order");
        }
        assertEquals(1, deliveredOn.size(), "one thread delivered them: " + deliveredOn);
        String reader = deliveredOn.iterator().next();
        assertTrue(reader.startsWith("mw-msg-client-tcp-") && reader.contains("-read-"), "listeners ran on the link's reader thread, not on " + reader);
    }

    @Test
    void closingTheNodeWhileACallerReadsEndsItsWaitAndTheLinksThreads() throws Exception {
        MessagingNode server = node("server", NO_SPIN, true);
        server.addMessageListener("silent", null, m -> { });
        MessagingNode client = node("client", NO_SPIN, false);
        UUID id = client.sendMessage("server", server.address("tcp"), null, "silent", "a", "say");
        List<Thread> a = new ArrayList<>();
        CompletableFuture<Message> waiting = onThread("caller-a", () -> client.waitForReply(id, Duration.ofMinutes(5)), a);
        AtomicInteger nudges = new AtomicInteger();
        Await.until("caller a reads the link itself", WAIT, () -> {
            server.subscribeMessage("nudge-" + nudges.incrementAndGet(), null);
            return leads(a.get(0));
        });
        client.close();
        Throwable e = failure(waiting);
        assertInstanceOf(MessagingException.class, e, "the wait ended when the node closed, long before its 5 minutes");
        assertTrue(e.getMessage().contains("closed"), e.getMessage());
        Await.until("the client's connection threads ended", WAIT, () -> Thread.getAllStackTraces().keySet().stream()
                .noneMatch(t -> t.getName().startsWith("mw-msg-client-tcp-")));
    }

    @Test
    void anInterruptedCallerStopsReadingAndTheLinkGoesOn() throws Exception {
        MessagingNode server = node("server", NO_SPIN, true);
        server.addMessageListener("silent", null, m -> { });
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", NO_SPIN, false);
        String host = server.address("tcp");
        UUID id = client.sendMessage("server", host, null, "silent", "a", "say");
        List<Thread> a = new ArrayList<>();
        CompletableFuture<Message> waiting = onThread("caller-a", () -> client.waitForReply(id, Duration.ofMinutes(5)), a);
        AtomicInteger nudges = new AtomicInteger();
        Await.until("caller a reads the link itself", WAIT, () -> {
            server.subscribeMessage("nudge-" + nudges.incrementAndGet(), null);
            return leads(a.get(0));
        });
        a.get(0).interrupt();
        Throwable e = failure(waiting);
        assertInstanceOf(MessagingException.class, e);
        assertTrue(e.getMessage().contains("interrupted"), e.getMessage());
        for (int i = 0; i < 20; i++) {
            UUID next = client.sendMessage("server", host, null, "echo", i, "say");
            assertEquals(i, client.waitForReply(next, WAIT).payload());
        }
    }

    @Test
    void aCallerReadingAQuietLinkLongerThanTheIdleTimeoutKeepsItOpen() throws Exception {
        // The peers' keep-alives come every third of the idle timeout; the reading caller takes them
        // as the reader thread would, and the link's idle timeout never fires.
        MessagingSettings quick = NO_SPIN.withLimits(PeerLimits.defaults().withTimeouts(Duration.ofMillis(600), Duration.ofMillis(600)));
        MessagingNode server = node("server", quick, true);
        server.addMessageListener("silent", null, m -> { });
        server.addMessageListener("echo", null, m -> server.replyMessage(m, m.payload(), "ok"));
        MessagingNode client = node("client", quick, false);
        String host = server.address("tcp");
        UUID id = client.sendMessage("server", host, null, "silent", "a", "say");
        long start = System.nanoTime();
        MessagingException e = org.junit.jupiter.api.Assertions.assertThrows(MessagingException.class,
                () -> client.waitForReply(id, Duration.ofMillis(2500)));
        assertTrue(e.getMessage().contains("no reply"), "the wait ran out, the link did not close: " + e.getMessage());
        assertTrue(System.nanoTime() - start >= Duration.ofMillis(2500).toNanos());
        assertEquals(0, client.stats().dropped(DropReason.TIMED_OUT));
        assertEquals(0, server.stats().dropped(DropReason.TIMED_OUT));
        UUID next = client.sendMessage("server", host, null, "echo", "still open", "say");
        assertEquals("still open", client.waitForReply(next, WAIT).payload());
        assertEquals(0, client.stats().droppedTotal());
    }

    // ---- a raw peer speaking frames ----

    private static Frame nextRequest(FrameStreamReader in) throws Exception {
        while (true) {
            int length = in.next();
            if (length < 0) {
                throw new IOException("the client closed the connection");
            }
            Frame f = FrameCodec.decode(in.buffer(), in.offset(), length, 1 << 20);
            if (f.kind() == FrameKind.MESSAGE) {
                return f;
            }
        }
    }

    private static final AtomicInteger NUMBERS = new AtomicInteger();

    private static byte[] frame(FrameKind kind, UUID correlationId, String receiver, String topic, int payloadType, byte[] payload) {
        Frame f = new Frame(kind, 0, 99, NUMBERS.incrementAndGet(), correlationId, MessagingNode.nowMicros(), "raw", receiver, topic, "say",
                payloadType, payload, false);
        return FrameCodec.encode(f, false);
    }

    private static void write(OutputStream out, byte[] frame) {
        try {
            out.write(frame);
            out.flush();
        } catch (IOException e) {
            throw new java.io.UncheckedIOException(e);
        }
    }
}
