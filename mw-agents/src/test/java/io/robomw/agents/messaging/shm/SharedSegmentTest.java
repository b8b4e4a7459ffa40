package io.robomw.agents.messaging.shm;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.spi.Publication;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The publisher's ring and a subscriber's view of it, on real mapped files in a temporary folder. */
class SharedSegmentTest {

    private static final int RING = 1 << 20;
    private static final long SHORT_TIMEOUT = TimeUnit.MILLISECONDS.toNanos(300);
    private static final long LONG_TIMEOUT = TimeUnit.SECONDS.toNanos(20);

    @TempDir
    Path dir;
    private final List<AutoCloseable> open = new ArrayList<>();

    @AfterEach
    void close() throws Exception {
        for (AutoCloseable c : open) {
            c.close();
        }
    }

    private SharedSegment segment(int ring, int cells) throws IOException {
        SharedSegment s = SharedSegment.create(dir, ring, cells);
        open.add(s);
        return s;
    }

    /** A subscriber: its cell in the segment, its mapping, and the reference frames its connection got. */
    private final class Sub {
        final SharedSegment.Subscriber cell;
        final SegmentView view;
        final List<byte[]> queued = new ArrayList<>();
        final AtomicInteger closedForLagging = new AtomicInteger();

        Sub(SharedSegment segment) throws IOException {
            cell = segment.attach(closedForLagging::incrementAndGet);
            assertNotNull(cell, "a free cell");
            view = SegmentView.open(dir, new Handshake.Offer(cell.cell(), segment.nonce(), segment.file()), "test-publisher", 4 << 20);
            open.add(view);
            cell.activate();
        }

        void send(SharedSegment segment, byte[] publication, long timeout) throws IOException {
            segment.send(publication, cell, f -> queued.add(f.clone()), timeout);
        }

        void send(SharedSegment segment, Publication publication, long timeout) throws IOException {
            segment.send(publication, cell, f -> queued.add(f.clone()), timeout);
        }

        /** Takes the oldest queued reference out, as the connection's reader would. */
        byte[] takeNext() throws FrameException {
            byte[] f = queued.remove(0);
            assertEquals(FrameKind.PUBLISH_SHARED.code(), f[FrameCodec.KIND_OFFSET]);
            return view.take(SharedReference.read(f, 0, f.length));
        }
    }

    static byte[] publication(int size, int seed) {
        byte[] payload = new byte[size];
        new java.util.Random(seed).nextBytes(payload);
        return FrameCodec.encode(new Frame(FrameKind.PUBLISH, 0, 1, seed, new UUID(1, seed), 0, "pub", "", "scan", "data",
                PayloadCodec.BYTES, payload, false), false);
    }

    static byte[] payloadOf(byte[] publication) throws FrameException {
        return FrameCodec.decode(publication, 0, publication.length, Integer.MAX_VALUE).payload();
    }

    @Test
    void aPublicationSentToSeveralSubscribersIsWrittenOnceAndEachTakesItIntact() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Sub a = new Sub(segment);
        Sub b = new Sub(segment);
        byte[] p = publication(100_000, 1);
        a.send(segment, p, LONG_TIMEOUT);
        b.send(segment, p, LONG_TIMEOUT);
        assertArrayEquals(a.queued.get(0), b.queued.get(0), "one record, one reference frame for both");
        assertArrayEquals(payloadOf(p), a.takeNext());
        assertArrayEquals(payloadOf(p), b.takeNext());
    }

    /**
     * A publication that travels apart (its payload never copied into a frame) is written into the
     * ring once for all its subscribers, and its reference frame is the one its whole frame gets.
     */
    @Test
    void aPublicationSentApartIsWrittenOnceAndReferencedAsItsWholeFrameIs() throws Exception {
        SharedSegment segment = segment(RING, 4);
        byte[] whole = publication(100_000, 1);
        Publication apart = Publication.apart(FrameCodec.decode(whole, 0, whole.length, Integer.MAX_VALUE), null);
        List<Sub> both = List.of(new Sub(segment), new Sub(segment));
        for (Sub s : both) {
            s.send(segment, apart, LONG_TIMEOUT);
        }
        for (Sub s : both) {
            assertArrayEquals(SharedReference.frameFor(whole, 1, 0), s.queued.get(0), "record 1 at offset 0, referenced as its whole frame would be");
            assertArrayEquals(payloadOf(whole), s.takeNext());
        }
    }

    @Test
    void theRingWrapsAroundAndEveryPayloadComesOutIntactInOrder() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Sub a = new Sub(segment);
        // 300 KB records in a 1 MiB ring: the fourth does not fit before the end and goes to the start
        for (int i = 0; i < 40; i++) {
            byte[] p = publication(300_000 + i, i);
            a.send(segment, p, LONG_TIMEOUT);
            assertArrayEquals(payloadOf(p), a.takeNext(), "payload " + i);
        }
    }

    @Test
    void aFullRingWaitsForTheSubscriberToCopy() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Sub a = new Sub(segment);
        byte[] first = publication(400_000, 1);
        a.send(segment, first, LONG_TIMEOUT);
        a.send(segment, publication(400_000, 2), LONG_TIMEOUT);
        byte[] third = publication(400_000, 3);
        CompletableFuture<Void> sent = CompletableFuture.runAsync(() -> {
            try {
                segment.send(third, a.cell, f -> { }, LONG_TIMEOUT);
            } catch (IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
        });
        assertFalse(completesWithin(sent, Duration.ofMillis(200)), "a third 400 KB record does not fit a 1 MiB ring while two are held");
        assertArrayEquals(payloadOf(first), a.takeNext());
        sent.get(20, TimeUnit.SECONDS);
        assertEquals(0, a.closedForLagging.get());
    }

    @Test
    void aSubscriberThatHoldsARecordPastTheSendTimeoutIsClosedAndStopsCounting() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Sub slow = new Sub(segment);
        Sub fast = new Sub(segment);
        for (int i = 0; i < 2; i++) {
            byte[] p = publication(400_000, i);
            slow.send(segment, p, SHORT_TIMEOUT);
            fast.send(segment, p, SHORT_TIMEOUT);
            fast.takeNext();
        }
        byte[] p = publication(400_000, 9);
        fast.send(segment, p, SHORT_TIMEOUT); // waits the timeout, then closes the one that did not copy
        assertEquals(1, slow.closedForLagging.get(), "the lagging subscriber is told once");
        assertEquals(0, fast.closedForLagging.get());
        assertEquals(1, segment.attachedCount());
        assertArrayEquals(payloadOf(p), fast.takeNext());
    }

    @Test
    void aSubscriberThatDetachesNoLongerHoldsTheRing() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Sub gone = new Sub(segment);
        Sub stays = new Sub(segment);
        for (int i = 0; i < 2; i++) {
            byte[] p = publication(400_000, i);
            gone.send(segment, p, LONG_TIMEOUT);
            stays.send(segment, p, LONG_TIMEOUT);
            stays.takeNext();
        }
        gone.cell.detach(); // its connection closed
        long start = System.nanoTime();
        stays.send(segment, publication(400_000, 3), LONG_TIMEOUT);
        assertTrue(System.nanoTime() - start < LONG_TIMEOUT, "no wait for a subscriber that is gone");
        assertEquals(0, gone.closedForLagging.get());
    }

    @Test
    void aSubscriberThatWasNotSentARecordDoesNotHoldIt() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Sub other = new Sub(segment); // subscribes to another topic: gets none of these
        Sub a = new Sub(segment);
        for (int i = 0; i < 20; i++) {
            byte[] p = publication(400_000, i);
            a.send(segment, p, SHORT_TIMEOUT);
            assertArrayEquals(payloadOf(p), a.takeNext());
        }
        assertEquals(0, other.closedForLagging.get());
        assertEquals(0, a.closedForLagging.get());
    }

    @Test
    void closingUnlinksTheFileAndAWaitingPublisherFails() throws Exception {
        SharedSegment segment = segment(RING, 4);
        Path file = segment.file();
        assertTrue(Files.exists(file));
        assertEquals("rw-------", java.nio.file.attribute.PosixFilePermissions.toString(Files.getPosixFilePermissions(file)));
        assertTrue(file.getFileName().toString().startsWith("robomw-shm-" + ProcessHandle.current().pid() + "-"));
        segment.close();
        assertFalse(Files.exists(file));
        assertEquals(null, segment.attach(() -> { }), "no cells from a closed segment");
    }

    @Test
    void segmentsOfProcessesThatEndedAreRemovedAndOthersKept() throws Exception {
        Path dead = Files.createFile(dir.resolve(SegmentLayout.FILE_PREFIX + deadPid() + "-123.seg"));
        Path mine = Files.createFile(dir.resolve(SegmentLayout.FILE_PREFIX + ProcessHandle.current().pid() + "-456.seg"));
        Path other = Files.createFile(dir.resolve("something-else-1.seg"));
        assertEquals(1, SharedSegment.removeStale(dir));
        assertFalse(Files.exists(dead));
        assertTrue(Files.exists(mine));
        assertTrue(Files.exists(other));
    }

    /** @return a process id no process has now */
    private static long deadPid() throws Exception {
        Process p = new ProcessBuilder("true").start();
        assertTrue(p.waitFor(20, TimeUnit.SECONDS));
        io.robomw.testkit.Await.until("the process is gone", Duration.ofSeconds(20), () -> ProcessHandle.of(p.pid()).isEmpty());
        return p.pid();
    }

    private static boolean completesWithin(CompletableFuture<?> f, Duration d) {
        try {
            f.get(d.toMillis(), TimeUnit.MILLISECONDS);
            return true;
        } catch (java.util.concurrent.TimeoutException e) {
            return false;
        } catch (Exception e) {
            throw new AssertionError(e);
        }
    }
}
