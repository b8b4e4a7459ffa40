package io.robomw.platform.testkit;

import io.robomw.api.ManualClock;
import io.robomw.platform.link.LinkLostException;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The kit's fake link against {@link io.robomw.platform.link.Link}'s contract and its own promises:
 * pieces one read each, losses and failures in their place, answers to writes and frames, on time
 * on its clock or when released, reads that wait, block and end on a close, and a far end that can
 * be unplugged.
 */
class ScriptedLinkTest {

    private static final Duration LONG = Duration.ofSeconds(10);

    private final ExecutorService reader = Executors.newSingleThreadExecutor(r -> new Thread(r, "scripted-link-test-reader"));

    @AfterEach
    void stopReader() throws InterruptedException {
        reader.shutdownNow();
        assertTrue(reader.awaitTermination(10, TimeUnit.SECONDS), "the reader thread ended");
    }

    private static byte[] bytes(int... values) {
        byte[] out = new byte[values.length];
        for (int i = 0; i < values.length; i++) {
            out[i] = (byte) values[i];
        }
        return out;
    }

    /** @return what one read of at most {@code len} bytes returns */
    private static byte[] read(ScriptedLink link, int len, Duration timeout) throws IOException {
        byte[] buf = new byte[len];
        int n = link.read(buf, 0, len, timeout);
        return Arrays.copyOf(buf, n);
    }

    private static ScriptedLink opened(ScriptedLink link) throws IOException {
        link.open();
        return link;
    }

    private Future<byte[]> readInBackground(ScriptedLink link, int len, Duration timeout) {
        return reader.submit(() -> read(link, len, timeout));
    }

    @Test
    void shouldReturnOnePieceAReadAndKeepTheRestOfAPieceReadInPart() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().deliver(bytes(1, 2, 3)).deliver(bytes(4)));

        assertArrayEquals(bytes(1, 2), read(link, 2, LONG));
        assertArrayEquals(bytes(3), read(link, 8, LONG), "the rest of the piece, not merged with the next one");
        assertArrayEquals(bytes(4), read(link, 8, LONG));
        assertEquals(3, link.reads());
    }

    @Test
    void shouldThrowAScriptedLossNamingTheLinkInItsPlaceAndGoOnWithWhatFollows() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().deliver(bytes(1)).deliverLoss().deliver(bytes(2)).named("brick 7"));

        assertArrayEquals(bytes(1), read(link, 8, LONG));
        LinkLostException lost = assertThrows(LinkLostException.class, () -> read(link, 8, LONG));
        assertEquals("brick 7", lost.link());
        assertArrayEquals(bytes(2), read(link, 8, LONG));
        assertTrue(link.isOpen());
    }

    @Test
    void shouldThrowAScriptedFailureOnceAsItIs() throws IOException {
        OutOfMemoryError error = new OutOfMemoryError("injected");
        IllegalStateException unchecked = new IllegalStateException("one bad read");
        ScriptedLink link = opened(new ScriptedLink().deliverFailure(error).deliverFailure(unchecked).deliver(bytes(5)));

        assertSame(error, assertThrows(OutOfMemoryError.class, () -> read(link, 8, LONG)));
        assertSame(unchecked, assertThrows(IllegalStateException.class, () -> read(link, 8, LONG)));
        assertArrayEquals(bytes(5), read(link, 8, LONG));
        assertThrows(IllegalArgumentException.class, () -> link.deliverFailure(new Exception("checked")));
    }

    @Test
    void shouldAnswerEachWriteAndKeepWhatWasWritten() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().answering(w -> w[0] == 0 ? null : bytes(w[0] * 2)));

        link.write(bytes(9, 3, 4), 1, 1);
        link.write(bytes(0), 0, 1);
        link.write(bytes(5, 6), 0, 2);

        assertArrayEquals(bytes(6), read(link, 8, LONG));
        assertArrayEquals(bytes(10), read(link, 8, LONG), "the write answered with null had no answer");
        assertEquals(3, link.writes());
        assertEquals(List.of("[3]", "[0]", "[5, 6]"), link.eachWrite().stream().map(Arrays::toString).toList());
        assertArrayEquals(bytes(3, 0, 5, 6), link.written());
        assertArrayEquals(bytes(3, 0, 5, 6), link.takeWritten());
        link.write(bytes(7), 0, 1);
        assertArrayEquals(bytes(7), link.takeWritten(), "only what came since the last take");
        assertArrayEquals(bytes(3, 0, 5, 6, 7), link.written());
    }

    @Test
    void shouldAnswerEachWholeFrameHoweverTheWritesCutThem() throws IOException {
        List<String> frames = new ArrayList<>();
        ScriptedLink link = opened(new ScriptedLink().framedBy(Framing.lengthPrefixed16LittleEndian())
                .answering(frame -> {
                    frames.add(Arrays.toString(frame));
                    return bytes(frame[2]);
                }));

        link.write(bytes(1, 0, 0xA, 2, 0, 0xB, 0xC, 1), 0, 8); // two frames and the first byte of a third's length
        link.write(bytes(0, 0xD), 0, 2);

        assertEquals(List.of("[1, 0, 10]", "[2, 0, 11, 12]", "[1, 0, 13]"), frames);
        assertArrayEquals(bytes(0xA), read(link, 8, LONG), "each frame's answer is a piece of its own");
        assertArrayEquals(bytes(0xB), read(link, 8, LONG));
        assertArrayEquals(bytes(0xD), read(link, 8, LONG));
    }

    @Test
    void shouldCutFixedFrames() throws IOException {
        List<String> frames = new ArrayList<>();
        ScriptedLink link = opened(new ScriptedLink().framedBy(Framing.fixed(2)).answeringWith(f -> {
            frames.add(Arrays.toString(f));
            return Answer.none();
        }));

        link.write(bytes(1, 2, 3), 0, 3);
        link.write(bytes(4), 0, 1);

        assertEquals(List.of("[1, 2]", "[3, 4]"), frames);
    }

    @Test
    void shouldDeliverADelayedAnswerOnlyOnceItsClockReachesItsTime() throws IOException {
        ManualClock clock = new ManualClock();
        ScriptedLink link = opened(new ScriptedLink().clockedBy(clock).answeringWith(w -> Answer.of(w).after(Duration.ofMillis(30))));
        clock.advance(Duration.ofMillis(5));
        link.write(bytes(8), 0, 1);

        assertArrayEquals(bytes(), read(link, 8, Duration.ofMillis(20)), "not before its time");
        clock.advance(Duration.ofMillis(29));
        assertArrayEquals(bytes(), read(link, 8, Duration.ZERO));
        clock.advance(Duration.ofMillis(1));
        assertArrayEquals(bytes(8), read(link, 8, Duration.ZERO), "due 30 ms after the write, on the link's clock");
        assertEquals(List.of(5_000_000L), link.writeTimes());
    }

    @Test
    void shouldDeliverWhatArrivesInTheOrderItIsDue() throws IOException {
        ManualClock clock = new ManualClock();
        ScriptedLink link = opened(new ScriptedLink().clockedBy(clock).answeringWith(w -> w[0] == 1
                ? Answer.of(bytes(1)).after(Duration.ofMillis(20)).and(Answer.of(bytes(11)).after(Duration.ofMillis(20)))
                : Answer.of(bytes(2)).after(Duration.ofMillis(5))));

        link.write(bytes(1), 0, 1);
        link.write(bytes(2), 0, 1);
        link.deliver(bytes(3));
        clock.advance(Duration.ofMillis(10));
        link.write(bytes(4), 0, 1); // due at 15 ms: before the first answer, due at 20
        clock.advance(Duration.ofMillis(30));

        List<Integer> order = new ArrayList<>();
        for (int i = 0; i < 5; i++) {
            order.add((int) read(link, 8, Duration.ZERO)[0]);
        }
        assertEquals(List.of(3, 2, 2, 1, 11), order);
    }

    @Test
    void shouldWaitOnTheWallClockForAnAnswerDueWithinTheTimeout() throws Exception {
        ScriptedLink link = opened(new ScriptedLink().answeringWith(w -> Answer.of(w).after(Duration.ofMillis(80))));
        long start = System.nanoTime();
        link.write(bytes(4), 0, 1);

        assertArrayEquals(bytes(4), read(link, 8, LONG));
        assertTrue(System.nanoTime() - start >= 80_000_000L, "arrived after " + (System.nanoTime() - start) / 1e6 + " ms");
    }

    @Test
    void shouldHoldAnAnswerUntilItsLatchIsReleasedAndLetOthersPass() throws Exception {
        CountDownLatch release = new CountDownLatch(1);
        ScriptedLink link = opened(new ScriptedLink().answeringWith(w -> w[0] == 1 ? Answer.of(w).heldUntil(release) : Answer.of(w)));
        link.write(bytes(1), 0, 1);
        link.write(bytes(2), 0, 1);

        assertArrayEquals(bytes(2), read(link, 8, LONG), "what is not held arrives");
        assertArrayEquals(bytes(), read(link, 8, Duration.ofMillis(20)), "the held answer does not");
        Future<byte[]> held = readInBackground(link, 8, LONG);
        release.countDown();
        assertArrayEquals(bytes(1), held.get(10, TimeUnit.SECONDS));
    }

    @Test
    void shouldWaitOutItsTimeoutWhenNothingArrives() throws IOException {
        ScriptedLink link = opened(new ScriptedLink());
        long start = System.nanoTime();

        assertArrayEquals(bytes(), read(link, 8, Duration.ofMillis(100)));
        assertTrue(System.nanoTime() - start >= 100_000_000L, "returned after " + (System.nanoTime() - start) / 1e6 + " ms");
    }

    @Test
    void shouldReturnAtOnceWhenTimingOutAtOnceAndNothingIsDueInTime() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().timingOutAtOnce().answeringWith(w -> Answer.of(w).after(Duration.ofSeconds(30))));
        link.write(bytes(1), 0, 1);
        long start = System.nanoTime();

        assertArrayEquals(bytes(), read(link, 8, Duration.ofSeconds(20)));
        assertTrue(System.nanoTime() - start < 10_000_000_000L, "returned after " + (System.nanoTime() - start) / 1e6 + " ms");
    }

    @Test
    void shouldWakeAWaitingReadWhenAnotherThreadDelivers() throws Exception {
        ScriptedLink link = opened(new ScriptedLink());
        Future<byte[]> read = readInBackground(link, 8, Duration.ofSeconds(30));
        Await.until("the read is waiting", LONG, () -> link.reads() == 1);

        link.deliver(bytes(6));

        assertArrayEquals(bytes(6), read.get(10, TimeUnit.SECONDS));
    }

    @Test
    void shouldBlockReadsWhateverTheirTimeoutUntilReleased() throws Exception {
        ScriptedLink link = opened(new ScriptedLink().deliver(bytes(1)));
        link.blockReads();
        Future<byte[]> read = readInBackground(link, 8, Duration.ZERO);
        Await.until("the read is blocked", LONG, () -> link.blockedReads() == 1);
        assertFalse(read.isDone(), "a zero timeout does not end a blocked read");

        link.releaseReads();

        assertArrayEquals(bytes(1), read.get(10, TimeUnit.SECONDS));
        assertEquals(0, link.blockedReads());
    }

    @Test
    void shouldEndABlockedReadWithAnIOExceptionNamingTheLinkWhenClosed() throws Exception {
        ScriptedLink link = opened(new ScriptedLink().named("stuck tower"));
        link.blockReads();
        Future<byte[]> read = readInBackground(link, 8, LONG);
        Await.until("the read is blocked", LONG, () -> link.blockedReads() == 1);

        link.close();

        IOException closed = assertInstanceOf(IOException.class, assertThrows(ExecutionException.class, () -> read.get(10, TimeUnit.SECONDS)).getCause());
        assertTrue(closed.getMessage().contains("stuck tower") && closed.getMessage().contains("closed"), closed.getMessage());
    }

    @Test
    void shouldEndAWaitingReadWhenClosed() throws Exception {
        ScriptedLink link = opened(new ScriptedLink());
        Future<byte[]> read = readInBackground(link, 8, Duration.ofSeconds(30));
        Await.until("the read is waiting", LONG, () -> link.reads() == 1);

        link.close();

        assertInstanceOf(IOException.class, assertThrows(ExecutionException.class, () -> read.get(10, TimeUnit.SECONDS)).getCause());
    }

    @Test
    void shouldRefuseTransfersWhileClosedAndKeepWhatIsOnItsWayAcrossAReopen() throws IOException {
        ScriptedLink link = new ScriptedLink().named("serial /dev/pts/9").deliver(bytes(1));
        assertFalse(link.isOpen(), "a link is made closed");
        IOException closed = assertThrows(IOException.class, () -> read(link, 8, LONG));
        assertTrue(closed.getMessage().contains("serial /dev/pts/9"), closed.getMessage());
        assertThrows(IOException.class, () -> link.write(bytes(1), 0, 1));

        link.open();
        link.open();
        link.close();
        link.close();
        link.open();

        assertArrayEquals(bytes(1), read(link, 8, LONG), "what arrived before survives, as a serial port's input does");
        assertEquals(2, link.opens());
        assertEquals(1, link.closes());
        assertEquals(0, link.writes(), "a refused write is not taken");
    }

    @Test
    void shouldLoseTheOpenLinkWhenUnpluggedAndOpenOnlyOncePluggedIn() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().named("pluggable").answering(w -> w).deliver(bytes(1)));
        link.unplug();

        assertThrows(LinkLostException.class, () -> read(link, 8, LONG));
        LinkLostException lost = assertThrows(LinkLostException.class, () -> link.write(bytes(2), 0, 1));
        assertEquals("pluggable", lost.link());
        link.plugIn();
        assertThrows(LinkLostException.class, () -> link.write(bytes(2), 0, 1), "lost until closed and opened again");
        link.unplug();
        link.close();
        IOException refused = assertThrows(IOException.class, link::open);
        assertTrue(refused.getMessage().contains("pluggable"), refused.getMessage());

        link.plugIn();
        link.open();

        link.write(bytes(3), 0, 1);
        assertArrayEquals(bytes(3), read(link, 8, LONG), "what was on its way when unplugged is gone");
    }

    @Test
    void shouldFailTheNextWriteOnceWithoutTakingIt() throws IOException {
        RuntimeException injected = new RuntimeException(new LinkageError("one bad write"));
        ScriptedLink link = opened(new ScriptedLink().failNextWrite(injected).answering(w -> w));

        assertSame(injected, assertThrows(RuntimeException.class, () -> link.write(bytes(1), 0, 1)));
        link.write(bytes(2), 0, 1);

        assertEquals(1, link.writes());
        assertArrayEquals(bytes(2), read(link, 8, LONG), "the failed write was not answered");
    }

    @Test
    void shouldRunTheHookOnTheReadingThreadOnceEachPieceIsRead() throws IOException {
        AtomicInteger done = new AtomicInteger();
        List<String> threads = new ArrayList<>();
        ScriptedLink link = opened(new ScriptedLink().deliver(bytes(1, 2)).deliver(bytes(3)).afterReadingEachPiece(() -> {
            done.incrementAndGet();
            threads.add(Thread.currentThread().getName());
        }));

        read(link, 1, LONG);
        assertEquals(0, done.get(), "half a piece");
        read(link, 1, LONG);
        assertEquals(1, done.get());
        read(link, 8, LONG);
        assertEquals(2, done.get());
        assertEquals(List.of(Thread.currentThread().getName(), Thread.currentThread().getName()), threads);
    }

    @Test
    void shouldReturnNothingForAReadOfNoBytes() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().deliver(bytes(1)));

        assertEquals(0, link.read(new byte[4], 0, 0, LONG));
        assertArrayEquals(bytes(1), read(link, 8, LONG), "the piece is still there");
    }

    @Test
    void shouldRefuseAResponderThatAnswersNull() throws IOException {
        ScriptedLink link = opened(new ScriptedLink().named("careless").answeringWith(w -> null));

        NullPointerException e = assertThrows(NullPointerException.class, () -> link.write(bytes(1), 0, 1));
        assertTrue(e.getMessage().contains("careless") && e.getMessage().contains("Answer.none()"), e.getMessage());
    }

    @Test
    void shouldEndAWaitingReadWhenItsThreadIsInterrupted() throws Exception {
        ScriptedLink link = opened(new ScriptedLink());
        Future<byte[]> read = readInBackground(link, 8, Duration.ofSeconds(30));
        Await.until("the read is waiting", LONG, () -> link.reads() == 1);

        read.cancel(true);

        reader.shutdown();
        assertTrue(reader.awaitTermination(10, TimeUnit.SECONDS), "the interrupted read ended");
    }
}
