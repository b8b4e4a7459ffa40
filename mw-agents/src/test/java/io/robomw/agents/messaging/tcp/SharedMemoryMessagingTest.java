package io.robomw.agents.messaging.tcp;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Large publications between two nodes of this JVM over real loopback connections: through shared
 * memory by default, mixed in order with small frames; over TCP when it is off on either side.
 */
class SharedMemoryMessagingTest {

    private static final Duration WAIT = Duration.ofSeconds(30);
    private static final MessagingSettings SETTINGS = MessagingSettings.defaults().withMaxFrameSize(2 << 20);
    private final List<MessagingNode> nodes = new CopyOnWriteArrayList<>();

    @AfterEach
    void closeNodes() {
        nodes.forEach(MessagingNode::close);
    }

    private MessagingNode node(MessagingNode.Builder b) {
        MessagingNode n = b.build();
        nodes.add(n);
        return n;
    }

    /** @return the segment files this process has in /dev/shm */
    static List<Path> mySegments() throws IOException {
        try (Stream<Path> files = Files.list(Path.of("/dev/shm"))) {
            String mine = "robomw-shm-" + ProcessHandle.current().pid() + "-";
            return files.filter(f -> f.getFileName().toString().startsWith(mine)).toList();
        }
    }

    /** @return the non-zero consumed-sequence cells of a segment file (SegmentLayout), as each subscriber left it */
    static List<Long> consumedCells(Path segment) throws IOException {
        java.nio.ByteBuffer head = java.nio.ByteBuffer.allocate(4096).order(java.nio.ByteOrder.nativeOrder());
        try (var ch = java.nio.channels.FileChannel.open(segment)) {
            while (head.hasRemaining() && ch.read(head) > 0) {
                // the control area's first page
            }
        }
        int cells = Math.min(head.getInt(io.robomw.agents.messaging.shm.SegmentLayout.CELL_COUNT_OFFSET), (4096 - 64) / 64);
        List<Long> out = new ArrayList<>();
        for (int i = 0; i < cells; i++) {
            long v = head.getLong(io.robomw.agents.messaging.shm.SegmentLayout.cellOffset(i));
            if (v != 0) {
                out.add(v);
            }
        }
        return out;
    }

    /** What a subscriber received: each payload as it came, in order. */
    private static List<Object> subscribe(MessagingNode sub, String topic) {
        List<Object> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener(topic, null, m -> got.add(m.payload()));
        sub.subscribeMessage(topic, null);
        return got;
    }

    /** Large payloads (100 KB and 1 MiB) and small ones (an int, 10 bytes) interleaved, each large one different. */
    private static List<Object> mixed(int count) {
        List<Object> out = new ArrayList<>();
        java.util.Random random = new java.util.Random(36);
        for (int i = 0; i < count; i++) {
            byte[] big = new byte[i % 5 == 4 ? 1 << 20 : 100_000];
            random.nextBytes(big);
            out.add(big);
            out.add(i);
            out.add(new byte[] {(byte) i, 1, 2, 3, 4, 5, 6, 7, 8, 9});
        }
        return out;
    }

    private static void assertSame(List<Object> sent, List<Object> got) {
        assertEquals(sent.size(), got.size());
        for (int i = 0; i < sent.size(); i++) {
            if (sent.get(i) instanceof byte[] b) {
                assertArrayEquals(b, (byte[]) got.get(i), "payload " + i);
            } else {
                assertEquals(sent.get(i), got.get(i), "payload " + i);
            }
        }
    }

    private static void publishAll(MessagingNode pub, List<Object> payloads) {
        for (Object p : payloads) {
            pub.publishMessage("scan", (java.io.Serializable) p, "data", null);
        }
    }

    @Test
    void largePublicationsGoThroughSharedMemoryToEverySubscriberIntactAndInOrderWithSmallOnes() throws Exception {
        {
            MessagingNode pub = node(MessagingNode.builder("pub").settings(SETTINGS).replayDirectory(null).bind("tcp://127.0.0.1:0"));
            List<List<Object>> got = new ArrayList<>();
            for (int i = 0; i < 3; i++) {
                got.add(subscribe(node(MessagingNode.builder("sub-" + i).settings(SETTINGS).replayDirectory(null).connect(pub.address("tcp"))), "scan"));
            }
            Await.until("the publisher sees 3 subscribers", WAIT, () -> pub.subscriberCount("scan") == 3);
            List<Object> sent = mixed(60);
            publishAll(pub, sent);
            for (List<Object> g : got) {
                Await.until("every payload arrives", WAIT, () -> g.size() == sent.size());
                assertSame(sent, g);
            }
            assertEquals(1, mySegments().size(), "one segment for all subscribers: " + mySegments());
            // 60 large payloads: the first went over TCP with the offer, and the others until the acceptance came; from
            // then on each was written once (so at most 59 records), and every subscriber's cell says it copied the last
            List<Long> cells = consumedCells(mySegments().get(0));
            assertEquals(3, cells.size(), "three subscribers took payloads out of the segment: " + cells);
            assertTrue(cells.stream().distinct().count() == 1 && cells.get(0) <= 59, "each publication written once, each taken by all: " + cells);
            pub.close();
            assertEquals(List.of(), mySegments(), "the segment is removed when its publisher closes");
        }
    }

    @Test
    void whenTheSubscriberTurnsItOffEverythingGoesOverTcp() throws Exception {
        {
            MessagingNode pub = node(MessagingNode.builder("pub").settings(SETTINGS).replayDirectory(null).bind("tcp://127.0.0.1:0"));
            List<Object> got = subscribe(node(MessagingNode.builder("sub").settings(SETTINGS.withSharedMemory(false)).replayDirectory(null)
                    .connect(pub.address("tcp"))), "scan");
            Await.until("the publisher sees the subscriber", WAIT, () -> pub.subscriberCount("scan") == 1);
            List<Object> sent = mixed(10);
            publishAll(pub, sent);
            Await.until("every payload arrives", WAIT, () -> got.size() == sent.size());
            assertSame(sent, got);
            assertEquals(List.of(), mySegments(), "no segment is made for a subscriber that did not ask");
            assertEquals(0, pub.stats().droppedTotal() + nodes.get(1).stats().droppedTotal());
        }
    }

    @Test
    void whenThePublishersAddressTurnsItOffEverythingGoesOverTcp() throws Exception {
        {
            MessagingNode pub = node(MessagingNode.builder("pub").settings(SETTINGS).replayDirectory(null).bind("tcp://127.0.0.1:0?shm=off"));
            List<Object> got = subscribe(node(MessagingNode.builder("sub").settings(SETTINGS).replayDirectory(null).connect(pub.address("tcp"))), "scan");
            Await.until("the publisher sees the subscriber", WAIT, () -> pub.subscriberCount("scan") == 1);
            List<Object> sent = mixed(10);
            publishAll(pub, sent);
            Await.until("every payload arrives", WAIT, () -> got.size() == sent.size());
            assertSame(sent, got);
            assertEquals(List.of(), mySegments());
        }
    }

    @Test
    void aProtectedTopicsPublicationsNeverGoThroughSharedMemory() throws Exception {
        MessagingNode pub = node(MessagingNode.builder("pub").settings(SETTINGS).replayDirectory(null).bind("tcp://127.0.0.1:0"));
        MessagingNode sub = node(MessagingNode.builder("sub").settings(SETTINGS).replayDirectory(null).connect(pub.address("tcp")));
        List<Object> got = new CopyOnWriteArrayList<>();
        sub.addMessageListener("secret", "pw", m -> got.add(m.payload()));
        sub.subscribeMessage("secret", "pw");
        Await.until("the publisher sees the subscriber", WAIT, () -> pub.subscriberCount("secret") == 1);
        byte[] big = new byte[200_000];
        new java.util.Random(1).nextBytes(big);
        for (int i = 0; i < 5; i++) {
            pub.publishMessage("secret", big, "data", "pw");
        }
        Await.until("5 protected payloads arrive", WAIT, () -> got.size() == 5);
        for (Object g : got) {
            assertArrayEquals(big, (byte[]) g);
        }
        assertEquals(List.of(), mySegments(), "frames with an HMAC are not offered shared memory");
        assertEquals(0, sub.stats().droppedTotal());
    }

    @Test
    void theAddressOptionTakesOnlyOnOrOff() {
        MessagingNode pub = node(MessagingNode.builder("pub").settings(SETTINGS).replayDirectory(null));
        var e = org.junit.jupiter.api.Assertions.assertThrows(RuntimeException.class, () -> pub.bind("tcp://127.0.0.1:0?shm=maybe"));
        assertTrue(e.getMessage().contains("'on' or 'off'"), e.getMessage());
    }
}
