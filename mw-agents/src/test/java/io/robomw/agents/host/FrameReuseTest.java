package io.robomw.agents.host;

import io.robomw.agents.host.protocol.FrameBuffers;
import io.robomw.agents.host.security.FrameTag;
import io.robomw.agents.host.wire.WireFrames;
import io.robomw.agents.host.wire.WireReader;
import io.robomw.agents.host.wire.WireWriter;
import io.robomw.agents.host.trip.ResizingAgent;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import javax.crypto.spec.SecretKeySpec;
import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.Serializable;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Random;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotSame;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The reused arrays of large transfers (docs/benchmarks.md, "Agent hops, session 5"): a connection's
 * frame array ({@link WireReader}) and a host's outgoing frame arrays ({@link FrameBuffers}) carry
 * agent after agent, large and small, without one agent's bytes turning up in another's state, and
 * a frame cut short in a reused array is still refused.
 */
class FrameReuseTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("frame reuse test");
    private static final SecretKeySpec FRAME_KEY = new SecretKeySpec(new byte[32], "AES");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    private static byte[] random(int n, long seed) {
        byte[] b = new byte[n];
        new Random(seed).nextBytes(b);
        return b;
    }

    /** Frames as a peer writes them, one after the other, on one stream. */
    private static byte[] frames(byte[]... bodies) throws Exception {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        WireWriter w = new WireWriter(WireWriter.of(out));
        for (int i = 0; i < bodies.length; i++) {
            w.write(FRAME_KEY, WireFrames.DIRECTION_REQUEST, 0, 7, i + 1, bodies[i], 0, bodies[i].length);
        }
        return out.toByteArray();
    }

    /** Reads the next frame, checks its tag, and returns its body. */
    private static byte[] next(WireReader r, FrameTag tag) throws Exception {
        WireFrames.Header h = r.header();
        tag.start(FRAME_KEY, WireFrames.DIRECTION_REQUEST, h.seq(), true);
        byte[] f = r.frame(h, tag);
        assertTrue(tag.check(f, (int) h.frameLength() - WireFrames.TAG), "frame " + h.seq() + "'s tag checks in the reused array");
        return Arrays.copyOfRange(f, WireFrames.HEADER, WireFrames.HEADER + (int) h.length());
    }

    @Test
    void aConnectionReadsLargeSmallAndLargeFramesIntoOneArrayEachWhole() throws Exception {
        byte[] large = random(1 << 20, 1);
        byte[] small = random(300, 2);
        byte[] middle = random(700_000, 3);
        byte[] huge = random(WireReader.KEEP_MAX + 1, 4);
        WireReader r = new WireReader(new ByteArrayInputStream(frames(large, small, small, middle, huge, large)), null);
        FrameTag tag = new FrameTag();
        assertArrayEquals(large, next(r, tag));
        assertArrayEquals(small, next(r, tag), "a small frame after a large one: only its own bytes");
        assertArrayEquals(small, next(r, tag));
        WireFrames.Header h = r.header();
        tag.start(FRAME_KEY, WireFrames.DIRECTION_REQUEST, h.seq(), true);
        byte[] kept = r.frame(h, tag);
        assertTrue(tag.check(kept, (int) h.frameLength() - WireFrames.TAG));
        assertArrayEquals(middle, Arrays.copyOfRange(kept, WireFrames.HEADER, WireFrames.HEADER + middle.length));
        assertEquals(large.length + WireFrames.HEADER + WireFrames.TAG, kept.length, "the 700 kB frame went into the 1 MB frame's array");
        h = r.header();
        tag.start(FRAME_KEY, WireFrames.DIRECTION_REQUEST, h.seq(), true);
        byte[] own = r.frame(h, tag);
        assertNotSame(kept, own, "a frame larger than KEEP_MAX gets an array of its own");
        assertTrue(tag.check(own, own.length - WireFrames.TAG));
        h = r.header();
        tag.start(FRAME_KEY, WireFrames.DIRECTION_REQUEST, h.seq(), true);
        assertSame(kept, r.frame(h, tag), "and is not kept: the next frame goes into the kept array again");
        assertNull(r.header(), "the stream ends cleanly after the last frame");
    }

    @Test
    void aFrameCutShortInAReusedArrayIsRefusedAndItsStaleBytesDoNotCheck() throws Exception {
        byte[] large = random(1 << 20, 5);
        byte[] second = random(900_000, 6);
        byte[] stream = frames(large, second);
        // The second frame loses its last 100 kB: the array still holds the first frame's bytes there.
        byte[] cut = Arrays.copyOf(stream, stream.length - 100_000);
        WireReader r = new WireReader(new ByteArrayInputStream(cut), null);
        FrameTag tag = new FrameTag();
        assertArrayEquals(large, next(r, tag));
        WireFrames.Header h = r.header();
        tag.start(FRAME_KEY, WireFrames.DIRECTION_REQUEST, h.seq(), true);
        WireFrames.FrameRefused e = assertThrows(WireFrames.FrameRefused.class, () -> r.frame(h, tag));
        assertTrue(e.getMessage().contains("ended within a frame"), e.getMessage());

        // A frame whose last bytes were changed to what the array held before does not check either.
        byte[] forged = stream.clone();
        int secondStart = WireFrames.HEADER + large.length + WireFrames.TAG;
        int at = secondStart + WireFrames.HEADER + 500_000;
        System.arraycopy(stream, WireFrames.HEADER + 500_000, forged, at, 1000);
        WireReader r2 = new WireReader(new ByteArrayInputStream(forged), null);
        assertArrayEquals(large, next(r2, tag));
        WireFrames.Header h2 = r2.header();
        tag.start(FRAME_KEY, WireFrames.DIRECTION_REQUEST, h2.seq(), true);
        byte[] f = r2.frame(h2, tag);
        assertTrue(!tag.check(f, (int) h2.frameLength() - WireFrames.TAG), "a changed byte in a reused array fails the tag");
    }

    @Test
    void aLargeFrameTaggedWhileItIsWrittenIsByteForByteTheOneTaggedInline() throws Exception {
        java.util.concurrent.ExecutorService tagger = java.util.concurrent.Executors.newSingleThreadExecutor();
        try {
            for (int n : new int[] {0, 100, WireWriter.ONE_WRITE, WireWriter.ONE_WRITE + 1, 1 << 20, 3 * WireWriter.ONE_WRITE - 7}) {
                byte[] body = random(n + 10, n);
                ByteArrayOutputStream inline = new ByteArrayOutputStream();
                new WireWriter(WireWriter.of(inline)).write(FRAME_KEY, WireFrames.DIRECTION_REPLY, 0, 9, 42, body, 5, n);
                ByteArrayOutputStream parallel = new ByteArrayOutputStream();
                new WireWriter(WireWriter.of(parallel), tagger).write(FRAME_KEY, WireFrames.DIRECTION_REPLY, 0, 9, 42, body, 5, n);
                assertArrayEquals(inline.toByteArray(), parallel.toByteArray(), n + " bytes");
            }
            // A connection that fails mid-frame: the writer returns only once the tagger is done, and its next frame is whole.
            int[] writes = {0};
            ByteArrayOutputStream after = new ByteArrayOutputStream();
            WireWriter.Out stream = WireWriter.of(after);
            WireWriter w = new WireWriter(parts -> {
                if (writes[0]++ == 1) {
                    throw new java.io.IOException("connection reset");
                }
                stream.write(parts);
            }, tagger);
            byte[] first = random(1 << 20, 8);
            assertThrows(java.io.IOException.class, () -> w.write(FRAME_KEY, WireFrames.DIRECTION_REQUEST, 0, 7, 1, first, 0, first.length));
            after.reset();
            byte[] second = random(700_000, 9);
            w.write(FRAME_KEY, WireFrames.DIRECTION_REQUEST, 0, 7, 2, second, 0, second.length);
            WireReader r = new WireReader(new ByteArrayInputStream(after.toByteArray()), null);
            assertArrayEquals(second, next(r, new FrameTag()));
        } finally {
            tagger.shutdownNow();
        }
    }

    @Test
    void frameBuffersKeepOnlyLargeArraysAFewAtATimeAndNeverOneTwice() {
        FrameBuffers pool = new FrameBuffers();
        assertNull(pool.take(1 << 20), "nothing kept yet");
        pool.give(new byte[1000]);
        assertEquals(0, pool.kept(), "small arrays are not kept");
        pool.give(new byte[FrameBuffers.MAX_BYTES + 1]);
        assertEquals(0, pool.kept(), "nor very large ones");
        byte[] a = new byte[1 << 20];
        byte[] b = new byte[2 << 20];
        pool.give(b);
        pool.give(a);
        assertThrows(IllegalStateException.class, () -> pool.give(a));
        assertSame(a, pool.take(900_000), "the smallest that fits");
        assertNull(pool.take(3 << 20), "none fits");
        assertNull(pool.take(1000), "small frames are not served from the pool");
        for (int i = 0; i < FrameBuffers.MAX_KEPT + 2; i++) {
            pool.give(new byte[(1 << 20) + i]);
        }
        assertEquals(FrameBuffers.MAX_KEPT, pool.kept());
    }

    @Test
    void agentsOfChangingSizesHopingAtOnceArriveWithExactlyTheirOwnBytes() throws Exception {
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging());
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging());
        AgentHost b = start(AgentHost.builder("b").clusterKey(KEY).noMessaging());
        // Large, then small, then large again, and a size between: reused arrays longer than the frame.
        int[][] schedules = {
                {1 << 20, 100, 0, 1 << 20, 600_000, 10_000, 1 << 20, 50},
                {200, 1 << 20, 900_000, 100, 1 << 20, 0, 700_000, 1 << 20},
                {800_000, 800_000, 5, 1_000_000, 300_000, 1 << 20, 20, 400_000},
                {0, 0, 1 << 20, 1 << 20, 0, 1 << 20, 0, 1 << 20},
        };
        List<CompletableFuture<Serializable>> results = new ArrayList<>();
        for (int i = 0; i < schedules.length; i++) {
            ResizingAgent agent = new ResizingAgent(100 + i, schedules[i]);
            for (int s = 1; s < schedules[i].length; s++) {
                agent.itinerary().addStop(s % 2 == 1 ? a.address() : b.address());
            }
            agent.itinerary().addStop(home.address());
            results.add(home.agency().startTrip(agent).result());
        }
        for (int i = 0; i < results.size(); i++) {
            @SuppressWarnings("unchecked")
            List<String> log = (List<String>) results.get(i).get(60, TimeUnit.SECONDS);
            assertEquals(schedules[i].length, log.size(), log.toString());
            for (String line : log) {
                assertTrue(line.endsWith(" ok"), "agent " + i + ": " + log);
            }
        }
        assertTrue(a.wireFramesServed() >= 4 * 4 && b.wireFramesServed() >= 4 * 3, "the hops went on the wire: " + a.wireFramesServed() + " " + b.wireFramesServed());
    }

    private AgentHost start(AgentHostBuilder builder) throws Exception {
        return hosts.start(builder);
    }
}
