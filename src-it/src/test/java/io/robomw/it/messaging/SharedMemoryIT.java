package io.robomw.it.messaging;

import io.robomw.agents.messaging.MessagingNode;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.shm.SegmentLayout;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.nio.channels.FileChannel;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.stream.Stream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Large publications from this JVM to subscribers in another: through shared memory when both
 * sides have it on, intact and in order with small ones; over TCP when the subscribers turn it off
 * or cannot map the publisher's file; and no segment file left once the publisher closed.
 */
class SharedMemoryIT {

    private static final int COUNT = 40;
    private static final int SUBSCRIBERS = 3;
    private static final Duration WAIT = Duration.ofSeconds(60);
    private final List<AutoCloseable> open = new ArrayList<>();

    @AfterEach
    void close() throws Exception {
        for (int i = open.size() - 1; i >= 0; i--) {
            open.get(i).close();
        }
    }

    private MessagingNode publisher() {
        MessagingNode pub = MessagingNode.builder("shm-pub").settings(MessagingSettings.defaults().withMaxFrameSize(2 << 20)).replayDirectory(null)
                .bind("tcp://127.0.0.1:0").build();
        open.add(pub);
        return pub;
    }

    private PeerProcess subscribers(MessagingNode pub, String shm, String... jvmArgs) throws IOException {
        PeerProcess p = PeerProcess.start("shm-subscribers-" + shm, SharedMemorySubscriber.class.getName(), List.of(jvmArgs),
                List.of(pub.address("tcp"), String.valueOf(SUBSCRIBERS), shm, String.valueOf(COUNT)));
        open.add(p);
        p.expect("READY", WAIT);
        Await.until("the publisher sees " + SUBSCRIBERS + " subscribers", WAIT, () -> pub.subscriberCount("scan") == SUBSCRIBERS);
        return p;
    }

    private static void publish(MessagingNode pub) {
        for (int i = 0; i < COUNT; i++) {
            pub.publishMessage("scan", SharedMemorySubscriber.large(i), "data", null);
            pub.publishMessage("scan", i, "index", null);
        }
    }

    /** @return this JVM's segment files in /dev/shm */
    private static List<Path> mySegments() throws IOException {
        try (Stream<Path> files = Files.list(Path.of("/dev/shm"))) {
            String mine = SegmentLayout.FILE_PREFIX + ProcessHandle.current().pid() + "-";
            return files.filter(f -> f.getFileName().toString().startsWith(mine)).toList();
        }
    }

    /** @return the consumed-sequence cells of a segment that are not zero */
    private static List<Long> consumedCells(Path segment) throws IOException {
        ByteBuffer head = ByteBuffer.allocate(4096).order(ByteOrder.nativeOrder());
        try (FileChannel ch = FileChannel.open(segment)) {
            while (head.hasRemaining() && ch.read(head) > 0) {
                // the first page of the control area
            }
        }
        int cells = Math.min(head.getInt(SegmentLayout.CELL_COUNT_OFFSET), (4096 - SegmentLayout.CELLS_OFFSET) / SegmentLayout.CELL_BYTES);
        List<Long> out = new ArrayList<>();
        for (int i = 0; i < cells; i++) {
            long v = head.getLong(SegmentLayout.cellOffset(i));
            if (v != 0) {
                out.add(v);
            }
        }
        return out;
    }

    @Test
    void largePublicationsReachAnotherJvmThroughSharedMemoryIntactAndInOrder() throws Exception {
        MessagingNode pub = publisher();
        PeerProcess subs = subscribers(pub, "on");
        publish(pub);
        subs.expect("DONE", WAIT);
        List<Path> segments = mySegments();
        assertEquals(1, segments.size(), "one segment for the subscribers: " + segments);
        List<Long> cells = consumedCells(segments.get(0));
        assertEquals(SUBSCRIBERS, cells.size(), "every subscriber took payloads out of the segment: " + cells);
        assertTrue(cells.stream().distinct().count() == 1 && cells.get(0) < COUNT, "each written once and taken by all: " + cells);
        pub.close();
        assertEquals(List.of(), mySegments(), "the segment file is removed when the publisher closes");
    }

    @Test
    void subscribersWithSharedMemoryOffGetEverythingOverTcp() throws Exception {
        MessagingNode pub = publisher();
        PeerProcess subs = subscribers(pub, "off");
        publish(pub);
        subs.expect("DONE", WAIT);
        assertEquals(List.of(), mySegments(), "no segment for subscribers that did not ask");
    }

    @Test
    void subscribersThatCannotMapThePublishersFileGetEverythingOverTcp() throws Exception {
        MessagingNode pub = publisher();
        // the subscribers take themselves for another user: they refuse to map a file that is not their user's
        PeerProcess subs = subscribers(pub, "on", "-Duser.name=robomw-someone-else");
        publish(pub);
        subs.expect("DONE", WAIT);
        List<Path> segments = mySegments();
        assertEquals(1, segments.size(), "offered: " + segments);
        assertEquals(List.of(), consumedCells(segments.get(0)), "nobody took anything out of it");
        pub.close();
        assertEquals(List.of(), mySegments());
    }
}
