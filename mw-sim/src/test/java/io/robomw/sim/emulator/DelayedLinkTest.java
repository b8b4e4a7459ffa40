package io.robomw.sim.emulator;

import io.robomw.platform.link.Link;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The emulators' slow link over an in-memory one: bytes a driver writes at once reach the
 * emulator one by one at their own time on the wire, and a reply takes its bytes' time and the
 * latency to come back.
 */
class DelayedLinkTest {

    /** What the driver wrote, all at once; what the emulator wrote back, with when. */
    static class MemoryLink implements Link {
        final java.util.concurrent.LinkedBlockingDeque<byte[]> fromDriver = new java.util.concurrent.LinkedBlockingDeque<>();
        final List<Long> writtenAt = new ArrayList<>();

        @Override
        public void open() {
        }

        @Override
        public boolean isOpen() {
            return true;
        }

        @Override
        public synchronized void write(byte[] data, int off, int len) {
            writtenAt.add(System.nanoTime());
            notifyAll();
        }

        @Override
        public int read(byte[] buf, int off, int len, Duration timeout) throws java.io.IOException {
            byte[] next;
            try {
                next = fromDriver.pollFirst(timeout.toNanos(), java.util.concurrent.TimeUnit.NANOSECONDS); // a read that waits as a link's does
            } catch (InterruptedException e) {
                throw new java.io.IOException(e);
            }
            if (next == null) {
                return 0;
            }
            int n = Math.min(len, next.length);
            System.arraycopy(next, 0, buf, off, n);
            if (n < next.length) {
                synchronized (this) {
                    fromDriver.addFirst(java.util.Arrays.copyOfRange(next, n, next.length));
                }
            }
            return n;
        }

        @Override
        public String describe() {
            return "memory";
        }

        @Override
        public void close() {
        }
    }

    private static final LinkModel LINE = LinkModel.serial(9600, 10);

    /** Reads exactly n bytes the way an emulator does, and when the last of them arrived. */
    private static long readExactly(DelayedLink link, byte[] into, int n) throws Exception {
        int got = 0;
        while (got < n) {
            got += link.read(into, got, n - got, Duration.ofMillis(500));
        }
        return link.lastDeliveredAt();
    }

    private static void shouldDeliverEachCommandAtItsOwnTime(LinkModel model) throws Exception {
        MemoryLink memory = new MemoryLink();
        DelayedLink link = new DelayedLink(memory, model, io.robomw.api.spi.FailurePolicy.logging());
        try {
            long written = System.nanoTime();
            synchronized (memory) {
                memory.fromDriver.add(new byte[]{1, 2, 3, 4, 5, 6});
            }
            long perByte = model.transmissionNanos(1);
            long latency = model.latency().toNanos();
            byte[] first = new byte[2];
            long firstArrived = readExactly(link, first, 2);
            byte[] rest = new byte[4];
            long secondArrived = readExactly(link, rest, 2);
            long thirdArrived = readExactly(link, new byte[2], 2);
            assertArrayEquals(new byte[]{1, 2}, first);
            assertArrayEquals(new byte[]{3, 4, 0, 0}, rest);
            // The second command arrives two bytes' time after the first, not with the whole write.
            assertEquals(2 * perByte, secondArrived - firstArrived, perByte / 10.0);
            assertEquals(2 * perByte, thirdArrived - secondArrived, perByte / 10.0);
            // The first arrives its bytes' time and the latency after the link took the write from
            // the driver's side (exactly: a loaded host may take the write late, never deliver early).
            long takenAt = link.lastInboundAt();
            assertTrue(takenAt >= written, "the write was taken before it was written");
            assertEquals(latency + 2 * perByte, firstArrived - takenAt, perByte / 10.0,
                    "the first command arrived " + (firstArrived - takenAt) / 1e6 + " ms after the link took it");
            // The emulator does not see a byte before it has arrived.
            assertTrue(System.nanoTime() >= thirdArrived, "a byte was read before its arrival");
        } finally {
            link.close();
        }
    }

    @Test
    void shouldDeliverTheCommandsOfOneWriteEachAtItsOwnTimeOnASerialLine() throws Exception {
        shouldDeliverEachCommandAtItsOwnTime(LINE);
    }

    @Test
    void shouldDeliverTheCommandsOfOneWriteEachAtItsOwnTimeOverALinkWithLatency() throws Exception {
        shouldDeliverEachCommandAtItsOwnTime(LINE.withLatency(Duration.ofMillis(15)));
    }

    @Test
    void shouldSendARepliesBytesAtTheLinesPaceAfterTheLatency() throws Exception {
        MemoryLink memory = new MemoryLink();
        LinkModel model = LINE.withLatency(Duration.ofMillis(15));
        DelayedLink link = new DelayedLink(memory, model, io.robomw.api.spi.FailurePolicy.logging());
        try {
            long start = System.nanoTime();
            link.write(new byte[3], 0, 3);
            link.write(new byte[3], 0, 3);
            io.robomw.testkit.Await.until("both replies sent", Duration.ofSeconds(2), () -> {
                synchronized (memory) {
                    return memory.writtenAt.size() == 2;
                }
            });
            synchronized (memory) {
                long first = memory.writtenAt.get(0) - start;
                long second = memory.writtenAt.get(1) - start;
                // Latencies overlap: the second reply follows the first by its own bytes' time.
                assertTrue(first >= 15_000_000 + model.transmissionNanos(3), "first reply after " + first / 1e6 + " ms");
                assertTrue(second >= 15_000_000 + model.transmissionNanos(6), "second reply after " + second / 1e6 + " ms");
                assertTrue(second - first < 15_000_000, "the second reply waited for a latency of its own");
            }
        } finally {
            link.close();
        }
    }

    /** A link whose reads or writes throw what the test hands it, once each. */
    static final class FailingLink extends MemoryLink {
        final java.util.concurrent.ConcurrentLinkedQueue<Throwable> readFailures = new java.util.concurrent.ConcurrentLinkedQueue<>();
        final java.util.concurrent.ConcurrentLinkedQueue<RuntimeException> writeFailures = new java.util.concurrent.ConcurrentLinkedQueue<>();
        volatile boolean closed;

        @Override
        public int read(byte[] buf, int off, int len, Duration timeout) throws java.io.IOException {
            Throwable t = readFailures.poll();
            if (t instanceof Error e) {
                throw e;
            }
            if (t instanceof RuntimeException e) {
                throw e;
            }
            return super.read(buf, off, len, timeout);
        }

        @Override
        public synchronized void write(byte[] data, int off, int len) {
            RuntimeException e = writeFailures.poll();
            if (e != null) {
                throw e;
            }
            super.write(data, off, len);
        }

        @Override
        public boolean isOpen() {
            return !closed;
        }

        @Override
        public void close() {
            closed = true;
        }
    }

    private static final LinkModel LATENT = LINE.withLatency(Duration.ofMillis(5));

    @Test
    void shouldCloseTheLinkAndNameTheErrorWhenItsPumpDiesOfOne() throws Exception {
        FailingLink memory = new FailingLink();
        io.robomw.sim.RecordingFailures failures = new io.robomw.sim.RecordingFailures();
        OutOfMemoryError injected = new OutOfMemoryError("injected into the pump");
        memory.readFailures.add(injected);
        DelayedLink link = new DelayedLink(memory, LATENT, failures);
        try {
            io.robomw.testkit.Await.until("the pump's death reported", Duration.ofSeconds(10), () -> !failures.deaths().isEmpty());

            java.io.IOException e = org.junit.jupiter.api.Assertions.assertThrows(java.io.IOException.class,
                    () -> link.read(new byte[4], 0, 4, Duration.ofSeconds(5)), "the emulator's read ends instead of waiting for ever");

            assertTrue(e.getMessage().contains("OutOfMemoryError: injected into the pump"), e.getMessage());
            assertEquals(List.of(new io.robomw.sim.RecordingFailures.Report("memory-in", injected, true)), failures.reports());
            assertTrue(memory.closed, "the real link was closed: the driver sees it drop");
            org.junit.jupiter.api.Assertions.assertFalse(link.isOpen());
            io.robomw.testkit.Await.until("the pump and the sender ended", Duration.ofSeconds(10), () -> Thread.getAllStackTraces().keySet().stream()
                    .noneMatch(t -> (t.getName().equals("memory-in") || t.getName().equals("memory-out")) && t.isAlive()),
                    () -> Thread.getAllStackTraces().entrySet().stream().filter(t -> t.getKey().getName().startsWith("memory"))
                            .map(t -> t.getKey().getName() + " " + t.getKey().getState() + " " + java.util.Arrays.toString(t.getValue())).toList().toString());
        } finally {
            link.close();
        }
    }

    @Test
    void shouldReportAFailedReadOfThePumpAndDeliverWhatComesAfterIt() throws Exception {
        FailingLink memory = new FailingLink();
        io.robomw.sim.RecordingFailures failures = new io.robomw.sim.RecordingFailures();
        IllegalStateException injected = new IllegalStateException("one bad read");
        memory.readFailures.add(injected);
        DelayedLink link = new DelayedLink(memory, LATENT, failures);
        try {
            io.robomw.testkit.Await.until("the failed read reported", Duration.ofSeconds(10), () -> failures.count() == 1);
            memory.fromDriver.add(new byte[]{7, 8});

            byte[] got = new byte[2];
            readExactly(link, got, 2);

            assertArrayEquals(new byte[]{7, 8}, got);
            assertEquals(List.of(new io.robomw.sim.RecordingFailures.Report("memory-in", injected, false)), failures.reports());
        } finally {
            link.close();
        }
    }

    @Test
    void shouldReportAFailedWriteOfTheSenderAndSendTheNextReply() throws Exception {
        FailingLink memory = new FailingLink();
        io.robomw.sim.RecordingFailures failures = new io.robomw.sim.RecordingFailures();
        LinkageError injected = new LinkageError("one bad write");
        memory.writeFailures.add(new RuntimeException(injected));
        DelayedLink link = new DelayedLink(memory, LATENT, failures);
        try {
            link.write(new byte[]{1}, 0, 1);
            link.write(new byte[]{2}, 0, 1);

            io.robomw.testkit.Await.until("the second reply sent", Duration.ofSeconds(10), () -> {
                synchronized (memory) {
                    return memory.writtenAt.size() == 1;
                }
            });
            assertEquals(1, failures.count(), failures.reports().toString());
            assertEquals("memory-out", failures.reports().get(0).owner());
            org.junit.jupiter.api.Assertions.assertFalse(failures.reports().get(0).died());
        } finally {
            link.close();
        }
    }
}
