package io.robomw.agents.messaging.io;

import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import org.junit.jupiter.api.Test;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The frames waiting for one peer: order, stream sequence numbers, batching, room, closing. */
class OutboundBufferTest {

    private static final int FRAME = 48;

    /** A frame of {@code kind} whose last 8 bytes say who sent it and its number there. */
    private static byte[] frame(FrameKind kind, int sender, int number) {
        byte[] f = new byte[FRAME];
        f[FrameCodec.KIND_OFFSET] = (byte) kind.code();
        ByteBuffer.wrap(f).order(ByteOrder.BIG_ENDIAN).putInt(FRAME - 8, sender).putInt(FRAME - 4, number);
        return f;
    }

    /** Collects what the writer thread (or a sender) writes, and counts the writes and who made them. */
    private static final class Wire implements OutboundBuffer.Writer {
        final ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        final AtomicInteger writes = new AtomicInteger();
        private final List<String> threads = new ArrayList<>();

        @Override
        public synchronized void write(byte[] buf, int offset, int length) {
            bytes.write(buf, offset, length);
            writes.incrementAndGet();
            threads.add(Thread.currentThread().getName());
            notifyAll();
        }

        /** @return the name of the thread of each write so far, in order */
        synchronized List<String> threads() {
            return new ArrayList<>(threads);
        }

        synchronized byte[] await(int count, long timeoutNanos) throws InterruptedException {
            long deadline = System.nanoTime() + timeoutNanos;
            long left;
            while (bytes.size() < count && (left = deadline - System.nanoTime()) > 0) {
                TimeUnit.NANOSECONDS.timedWait(this, left);
            }
            return bytes.toByteArray();
        }

        synchronized byte[] taken() {
            return bytes.toByteArray();
        }
    }

    private static OutboundBuffer started(Wire wire, int capacity) {
        OutboundBuffer b = new OutboundBuffer("peer", capacity, TimeUnit.SECONDS.toNanos(5));
        b.startWriter(wire, r -> {
            Thread t = new Thread(r, "test-writer");
            t.setDaemon(true);
            return t;
        }, e -> { });
        return b;
    }

    private static byte[] awaitBytes(Wire wire, int count) throws InterruptedException {
        byte[] all = wire.await(count, TimeUnit.SECONDS.toNanos(10));
        assertEquals(count, all.length, "bytes written");
        return all;
    }

    @Test
    void framesFromManySendersGoOutWholeInEachSendersOrderWithConsecutiveStreamSequences() throws Exception {
        Wire wire = new Wire();
        OutboundBuffer buffer = started(wire, 1 << 20);
        int senders = 4;
        int each = 20_000;
        CountDownLatch start = new CountDownLatch(1);
        List<Thread> threads = new ArrayList<>();
        for (int s = 0; s < senders; s++) {
            int sender = s;
            Thread t = new Thread(() -> {
                try {
                    start.await();
                    for (int i = 0; i < each; i++) {
                        // mostly publications, now and then a request (written directly when the link is idle)
                        buffer.send(frame(i % 100 == 0 ? FrameKind.MESSAGE : FrameKind.PUBLISH, sender, i));
                    }
                } catch (IOException | InterruptedException e) {
                    throw new AssertionError(e);
                }
            }, "sender-" + s);
            threads.add(t);
            t.start();
        }
        start.countDown();
        for (Thread t : threads) {
            t.join(TimeUnit.SECONDS.toMillis(30));
        }
        ByteBuffer all = ByteBuffer.wrap(awaitBytes(wire, senders * each * FRAME));
        int[] next = new int[senders];
        for (long expectedSequence = 1; all.hasRemaining(); expectedSequence++) {
            int at = all.position();
            assertEquals(expectedSequence, all.getLong(at + FrameCodec.STREAM_SEQUENCE_OFFSET), "stream sequence at byte " + at);
            int sender = all.getInt(at + FRAME - 8);
            assertEquals(next[sender]++, all.getInt(at + FRAME - 4), "sender " + sender + "'s frames in the order it sent them");
            all.position(at + FRAME);
        }
        assertTrue(wire.writes.get() < senders * each / 10, "publications went out in batches: " + wire.writes.get() + " writes for " + senders * each + " frames");
        buffer.close();
    }

    @Test
    void aFastStreamIsWrittenByItsSenderInBatchesAndItsTailByTheWriterThread() throws Exception {
        Wire wire = new Wire();
        OutboundBuffer buffer = started(wire, 1 << 20);
        int frames = 100_000;
        Thread sender = new Thread(() -> {
            try {
                for (int i = 0; i < frames; i++) {
                    buffer.send(frame(FrameKind.PUBLISH, 0, i));
                }
            } catch (IOException e) {
                throw new AssertionError(e);
            }
        }, "stream-sender");
        sender.start();
        sender.join(TimeUnit.SECONDS.toMillis(30));
        ByteBuffer all = ByteBuffer.wrap(awaitBytes(wire, frames * FRAME));
        for (int i = 0; i < frames; i++) {
            assertEquals(i + 1, all.getLong(i * FRAME + FrameCodec.STREAM_SEQUENCE_OFFSET), "stream sequence of frame " + i);
            assertEquals(i, all.getInt(i * FRAME + FRAME - 4), "frame " + i + " in its place");
        }
        List<String> writers = wire.threads();
        // about 290 batches of 16 KiB; a sender also writes a publication that finds the link idle (5 of 135 writes
        // when only the writer thread wrote batches)
        long bySender = writers.stream().filter("stream-sender"::equals).count();
        assertTrue(bySender >= 50, "the sender wrote batches of its stream itself: " + bySender + " of " + writers.size() + " writes");
        assertTrue(writers.size() < frames / 100, "in batches: " + writers.size() + " writes for " + frames + " frames");
        buffer.close();
    }

    @Test
    void closeWritesWhatIsWaitingFirst() throws Exception {
        Wire wire = new Wire();
        OutboundBuffer buffer = started(wire, 1 << 20);
        for (int i = 0; i < 1000; i++) {
            buffer.send(frame(FrameKind.PUBLISH, 0, i));
        }
        buffer.close();
        assertTrue(buffer.awaitDrained(TimeUnit.SECONDS.toNanos(10)), "drained");
        assertEquals(1000 * FRAME, wire.taken().length);
        assertThrows(IOException.class, () -> buffer.send(frame(FrameKind.PUBLISH, 0, 1000)));
    }

    @Test
    void aSenderToAPeerThatDoesNotReadGetsAnErrorAfterTheSendTimeout() throws Exception {
        CountDownLatch never = new CountDownLatch(1);
        OutboundBuffer buffer = new OutboundBuffer("stuck-peer", 10 * FRAME, TimeUnit.MILLISECONDS.toNanos(200));
        buffer.startWriter((b, o, l) -> {
            // frames written directly by the sender (an idle link) go through; the writer thread's batch never does
            if (Thread.currentThread().getName().equals("stuck-writer")) {
                try {
                    never.await();
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            }
        }, r -> {
            Thread t = new Thread(r, "stuck-writer");
            t.setDaemon(true);
            return t;
        }, e -> { });
        IOException e = assertThrows(IOException.class, () -> {
            for (int i = 0; i < 100; i++) {
                buffer.send(frame(FrameKind.PUBLISH, 0, i));
            }
        });
        assertTrue(e.getMessage().contains("stuck-peer") && e.getMessage().contains("not reading"), e.getMessage());
        buffer.close();
    }

    /** A frame of {@code length} bytes of {@code kind} whose bytes after the head count up from {@code seed}. */
    private static byte[] large(FrameKind kind, int length, int seed) {
        byte[] f = new byte[length];
        f[FrameCodec.KIND_OFFSET] = (byte) kind.code();
        for (int i = OutboundBuffer.HEAD; i < length; i++) {
            f[i] = (byte) (seed + i);
        }
        return f;
    }

    @Test
    void largeFramesAmongSmallOnesGoOutWholeInOrderWithTheirOwnSequenceAndTheCallersArrayUnchanged() throws Exception {
        Wire wire = new Wire();
        OutboundBuffer buffer = started(wire, 8 << 20);
        List<byte[]> sent = new ArrayList<>();
        for (int i = 0; i < 12; i++) {
            byte[] f = i % 3 == 0 ? frame(FrameKind.PUBLISH, 0, i) : large(FrameKind.PUBLISH, OutboundBuffer.SHARED_FROM + 1000 * i, i);
            sent.add(f);
            buffer.send(f);
        }
        int total = sent.stream().mapToInt(f -> f.length).sum();
        byte[] all = awaitBytes(wire, total);
        int at = 0;
        for (int i = 0; i < sent.size(); i++) {
            byte[] f = sent.get(i);
            assertEquals(0L, ByteBuffer.wrap(f).getLong(FrameCodec.STREAM_SEQUENCE_OFFSET), "the caller's frame " + i + " is not stamped");
            assertEquals(i + 1L, ByteBuffer.wrap(all).getLong(at + FrameCodec.STREAM_SEQUENCE_OFFSET), "sequence of frame " + i);
            assertTrue(java.util.Arrays.equals(f, OutboundBuffer.HEAD, f.length, all, at + OutboundBuffer.HEAD, at + f.length),
                    "bytes of frame " + i);
            at += f.length;
        }
        buffer.close();
    }

    @Test
    void aPeerThatFetchesTakesLargeFramesWhole() throws Exception {
        OutboundBuffer buffer = new OutboundBuffer("peer", 8 << 20, TimeUnit.SECONDS.toNanos(5));
        byte[] small = frame(FrameKind.MESSAGE, 1, 1);
        byte[] big = large(FrameKind.PUBLISH, OutboundBuffer.SHARED_FROM, 7);
        buffer.send(small);
        buffer.send(big);
        buffer.send(small);

        byte[] all = buffer.take(TimeUnit.SECONDS.toNanos(1));

        assertEquals(2 * small.length + big.length, all.length);
        assertEquals(2L, ByteBuffer.wrap(all).getLong(small.length + FrameCodec.STREAM_SEQUENCE_OFFSET));
        assertTrue(java.util.Arrays.equals(big, OutboundBuffer.HEAD, big.length, all, small.length + OutboundBuffer.HEAD, small.length + big.length));
        assertEquals(3L, ByteBuffer.wrap(all).getLong(small.length + big.length + FrameCodec.STREAM_SEQUENCE_OFFSET));
        assertEquals(0, buffer.take(1).length, "nothing left");
    }
}
