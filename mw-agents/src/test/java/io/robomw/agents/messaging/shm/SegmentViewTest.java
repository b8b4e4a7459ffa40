package io.robomw.agents.messaging.shm;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameException;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** What a subscriber refuses: files that are not the offered segment, and references that do not hold. */
class SegmentViewTest {

    private static final int RING = 1 << 20;

    @TempDir
    Path dir;
    private final List<AutoCloseable> open = new ArrayList<>();
    private SharedSegment segment;
    private SharedSegment.Subscriber cell;
    private final List<byte[]> queued = new ArrayList<>();

    @AfterEach
    void close() throws Exception {
        for (AutoCloseable c : open) {
            c.close();
        }
    }

    private SegmentView view() throws IOException {
        segment = SharedSegment.create(dir, RING, 4);
        open.add(segment);
        cell = segment.attach(() -> { });
        SegmentView v = SegmentView.open(dir, new Handshake.Offer(cell.cell(), segment.nonce(), segment.file()), "peer", 4 << 20);
        open.add(v);
        cell.activate();
        return v;
    }

    private SharedReference publish(int size, int seed) throws IOException {
        segment.send(SharedSegmentTest.publication(size, seed), cell, f -> queued.add(f.clone()), 1_000_000_000L);
        byte[] f = queued.get(queued.size() - 1);
        try {
            return SharedReference.read(f, 0, f.length);
        } catch (FrameException e) {
            throw new AssertionError(e);
        }
    }

    private static void refused(String containing, SegmentView v, SharedReference ref) {
        FrameException e = assertThrows(FrameException.class, () -> v.take(ref));
        assertEquals(DropReason.MALFORMED, e.reason());
        assertTrue(e.getMessage().contains(containing), e.getMessage());
    }

    @Test
    void referencesOutsideTheRingOrUnalignedAreRefused() throws Exception {
        SegmentView v = view();
        SharedReference ok = publish(1000, 1);
        refused("outside", v, new SharedReference(ok.sequence(), RING - 8, 1000));
        refused("outside", v, new SharedReference(ok.sequence(), 0, RING));
        refused("outside", v, new SharedReference(ok.sequence(), -8, 1000));
        refused("outside", v, new SharedReference(ok.sequence(), 0, -1));
        refused("aligned", v, new SharedReference(ok.sequence(), 4, 1000));
        assertArrayEquals(SharedSegmentTest.payloadOf(SharedSegmentTest.publication(1000, 1)), v.take(ok), "a good one still comes out");
    }

    @Test
    void aReferenceThatDoesNotMatchItsRecordIsRefused() throws Exception {
        SegmentView v = view();
        SharedReference ok = publish(1000, 1);
        refused("holds sequence", v, new SharedReference(ok.sequence() + 1, ok.offset(), ok.length()));
        refused("holds sequence", v, new SharedReference(ok.sequence(), ok.offset(), ok.length() - 1));
    }

    @Test
    void referencesOutOfOrderAreRefused() throws Exception {
        SegmentView v = view();
        SharedReference first = publish(1000, 1);
        SharedReference second = publish(1000, 2);
        v.take(second);
        refused("does not follow", v, first);
        refused("does not follow", v, second);
    }

    @Test
    void anOfferOfAnotherFileOrWithAnotherNonceIsRefused() throws Exception {
        view();
        Path elsewhere = Files.createFile(dir.resolve("not-a-segment"));
        assertThrows(IOException.class, () -> SegmentView.open(dir, new Handshake.Offer(0, segment.nonce(), elsewhere), "peer", 4 << 20));
        assertThrows(IOException.class, () -> SegmentView.open(dir.resolve("sub"), new Handshake.Offer(0, segment.nonce(), segment.file()), "peer", 4 << 20));
        IOException nonce = assertThrows(IOException.class,
                () -> SegmentView.open(dir, new Handshake.Offer(0, segment.nonce() + 1, segment.file()), "peer", 4 << 20));
        assertTrue(nonce.getMessage().contains("nonce"), nonce.getMessage());
        assertThrows(IOException.class, () -> SegmentView.open(dir, new Handshake.Offer(4, segment.nonce(), segment.file()), "peer", 4 << 20), "cell 4 of 4");
        Path link = Files.createSymbolicLink(dir.resolve(SegmentLayout.FILE_PREFIX + "link"), segment.file());
        assertThrows(IOException.class, () -> SegmentView.open(dir, new Handshake.Offer(0, segment.nonce(), link), "peer", 4 << 20));
        Path small = Files.write(dir.resolve(SegmentLayout.FILE_PREFIX + "small"), new byte[10]);
        assertThrows(IOException.class, () -> SegmentView.open(dir, new Handshake.Offer(0, segment.nonce(), small), "peer", 4 << 20));
    }

    @Test
    void aPayloadAboveTheSubscribersMaximumFrameSizeIsRefused() throws Exception {
        view();
        SharedReference big = publish(2000, 1);
        try (SegmentView small = SegmentView.open(dir, new Handshake.Offer(cell.cell(), segment.nonce(), segment.file()), "peer", 1024)) {
            FrameException e = assertThrows(FrameException.class, () -> small.take(big));
            assertEquals(DropReason.OVERSIZED, e.reason());
        }
    }

    @Test
    void aClosedViewRefusesReferences() throws Exception {
        SegmentView v = view();
        SharedReference ok = publish(1000, 1);
        v.close();
        refused("closed", v, ok);
    }
}
