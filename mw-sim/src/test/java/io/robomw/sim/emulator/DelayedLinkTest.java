package io.robomw.sim.emulator;

import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The emulators' slow link over an in-memory one: bytes a driver writes at once reach the
 * emulator one by one at their own time on the wire, and a reply takes its bytes' time and the
 * latency to come back.
 */
class DelayedLinkTest {

    /**
     * The real link under the delayed one, in memory: what the test delivers is what the driver
     * wrote, all at once; its writes (stamped on the wall clock) are what the emulator wrote back.
     */
    private static ScriptedLink memory() throws java.io.IOException {
        ScriptedLink memory = new ScriptedLink().named("memory");
        memory.open();
        return memory;
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
        ScriptedLink memory = memory();
        DelayedLink link = new DelayedLink(memory, model, io.robomw.api.spi.FailurePolicy.logging());
        try {
            long written = System.nanoTime();
            memory.deliver(new byte[]{1, 2, 3, 4, 5, 6});
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
        ScriptedLink memory = memory();
        // A latency long beside a loaded machine's stalls: whether the second reply waited a latency
        // of its own (half a second more) or not (its bytes' time) stays clear under load.
        long latency = 500_000_000L;
        LinkModel model = LINE.withLatency(Duration.ofNanos(latency));
        DelayedLink link = new DelayedLink(memory, model, io.robomw.api.spi.FailurePolicy.logging());
        try {
            long start = System.nanoTime();
            link.write(new byte[3], 0, 3);
            link.write(new byte[3], 0, 3);
            io.robomw.testkit.Await.until("both replies sent", Duration.ofSeconds(10), () -> memory.writes() == 2);
            long first = memory.writeTimes().get(0) - start;
            long second = memory.writeTimes().get(1) - start;
            // Latencies overlap: the second reply follows the first by its own bytes' time.
            assertTrue(first >= latency + model.transmissionNanos(3), "first reply after " + first / 1e6 + " ms");
            assertTrue(second >= latency + model.transmissionNanos(6), "second reply after " + second / 1e6 + " ms");
            assertTrue(second - first < latency, "the second reply waited for a latency of its own: " + (second - first) / 1e6 + " ms after the first");
        } finally {
            link.close();
        }
    }

    private static final LinkModel LATENT = LINE.withLatency(Duration.ofMillis(5));

    @Test
    void shouldCloseTheLinkAndNameTheErrorWhenItsPumpDiesOfOne() throws Exception {
        ScriptedLink memory = memory();
        io.robomw.testkit.RecordingFailures failures = new io.robomw.testkit.RecordingFailures();
        OutOfMemoryError injected = new OutOfMemoryError("injected into the pump");
        memory.deliverFailure(injected);
        DelayedLink link = new DelayedLink(memory, LATENT, failures);
        try {
            io.robomw.testkit.Await.until("the pump's death reported", Duration.ofSeconds(10), () -> !failures.deaths().isEmpty());

            java.io.IOException e = org.junit.jupiter.api.Assertions.assertThrows(java.io.IOException.class,
                    () -> link.read(new byte[4], 0, 4, Duration.ofSeconds(5)), "the emulator's read ends instead of waiting for ever");

            assertTrue(e.getMessage().contains("OutOfMemoryError: injected into the pump"), e.getMessage());
            assertEquals(List.of(new io.robomw.testkit.RecordingFailures.Report("memory-in", injected, true)), failures.reports());
            assertFalse(memory.isOpen(), "the real link was closed: the driver sees it drop");
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
        ScriptedLink memory = memory();
        io.robomw.testkit.RecordingFailures failures = new io.robomw.testkit.RecordingFailures();
        IllegalStateException injected = new IllegalStateException("one bad read");
        memory.deliverFailure(injected);
        DelayedLink link = new DelayedLink(memory, LATENT, failures);
        try {
            io.robomw.testkit.Await.until("the failed read reported", Duration.ofSeconds(10), () -> failures.count() == 1);
            memory.deliver(new byte[]{7, 8});

            byte[] got = new byte[2];
            readExactly(link, got, 2);

            assertArrayEquals(new byte[]{7, 8}, got);
            assertEquals(List.of(new io.robomw.testkit.RecordingFailures.Report("memory-in", injected, false)), failures.reports());
        } finally {
            link.close();
        }
    }

    @Test
    void shouldReportAFailedWriteOfTheSenderAndSendTheNextReply() throws Exception {
        ScriptedLink memory = memory();
        io.robomw.testkit.RecordingFailures failures = new io.robomw.testkit.RecordingFailures();
        LinkageError injected = new LinkageError("one bad write");
        memory.failNextWrite(new RuntimeException(injected));
        DelayedLink link = new DelayedLink(memory, LATENT, failures);
        try {
            link.write(new byte[]{1}, 0, 1);
            link.write(new byte[]{2}, 0, 1);

            io.robomw.testkit.Await.until("the second reply sent", Duration.ofSeconds(10), () -> memory.writes() == 1);
            assertEquals(1, failures.count(), failures.reports().toString());
            assertEquals("memory-out", failures.reports().get(0).owner());
            org.junit.jupiter.api.Assertions.assertFalse(failures.reports().get(0).died());
        } finally {
            link.close();
        }
    }
}
