package io.robomw.platform.rcx;

import io.robomw.testkit.Await;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.LinkTimeoutException;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.PriorityQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * An RCX whose answers to a request come after the driver gave up on it (a busy host, a slow IR
 * line): the late echo and reply must not be taken for the next request's, which would mark a good
 * link lost. With the serial tower, which echoes, and the USB one, which does not.
 */
class RcxBrickLateAnswerTest {

    private static final Duration REPLY_TIMEOUT = Duration.ofMillis(150);
    private static final int BATTERY = 7_654;

    /**
     * A tower and brick that answer each packet written with its echo (if the tower echoes) and
     * the reply, after the delay the test queued for that packet (5 ms when none is queued). Bytes
     * come out in the order they are due; closing and reopening keeps them, as a serial port's
     * input buffer does.
     */
    private static final class LateBrick implements Link {
        private final boolean echo;
        private final ReentrantLock lock = new ReentrantLock();
        private final Condition changed = lock.newCondition();
        private final PriorityQueue<long[]> due = new PriorityQueue<>((a, b) -> a[0] != b[0] ? Long.compare(a[0], b[0]) : Long.compare(a[1], b[1]));
        private final java.util.Map<Long, byte[]> bytesOf = new java.util.HashMap<>();
        private final Deque<Long> delaysMillis = new ArrayDeque<>();
        private long sequence;
        private byte[] head;
        private int headAt;

        LateBrick(boolean echo) {
            this.echo = echo;
        }

        void delayNext(long... millis) {
            lock.lock();
            try {
                for (long m : millis) {
                    delaysMillis.add(m);
                }
            } finally {
                lock.unlock();
            }
        }

        /** Puts bytes on the line now, as noise would. */
        void noise(byte... bytes) {
            schedule(0, bytes);
        }

        private void schedule(long delayMillis, byte[] bytes) {
            lock.lock();
            try {
                long id = sequence++;
                due.add(new long[]{System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(delayMillis), id});
                bytesOf.put(id, bytes);
                changed.signalAll();
            } finally {
                lock.unlock();
            }
        }

        @Override
        public void open() {
        }

        @Override
        public boolean isOpen() {
            return true;
        }

        @Override
        public void write(byte[] data, int off, int len) {
            byte[] packet = java.util.Arrays.copyOfRange(data, off, off + len);
            RcxPacket.Decoded request = RcxPacket.decode(packet);
            int op = request.opcode();
            byte[] data2 = new byte[RcxPacket.replyDataLength(op)];
            if (data2.length == 2) {
                data2[0] = (byte) BATTERY;
                data2[1] = (byte) (BATTERY >> 8);
            }
            byte[] reply = RcxPacket.encode(RcxPacket.replyOpcode(op), data2);
            long delay;
            lock.lock();
            try {
                delay = delaysMillis.isEmpty() ? 5 : delaysMillis.poll();
            } finally {
                lock.unlock();
            }
            byte[] answer = echo ? concat(packet, reply) : reply;
            schedule(delay, answer);
        }

        @Override
        public int read(byte[] buf, int off, int len, Duration timeout) {
            long deadline = System.nanoTime() + timeout.toNanos();
            lock.lock();
            try {
                while (true) {
                    if (head == null && !due.isEmpty() && due.peek()[0] <= System.nanoTime()) {
                        head = bytesOf.remove(due.poll()[1]);
                        headAt = 0;
                    }
                    if (head != null) {
                        int n = Math.min(len, head.length - headAt);
                        System.arraycopy(head, headAt, buf, off, n);
                        headAt += n;
                        if (headAt == head.length) {
                            head = null;
                        }
                        return n;
                    }
                    long now = System.nanoTime();
                    long wait = deadline - now;
                    if (wait <= 0) {
                        return 0;
                    }
                    if (!due.isEmpty()) {
                        wait = Math.min(wait, Math.max(1, due.peek()[0] - now));
                    }
                    changed.awaitNanos(wait);
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return 0;
            } finally {
                lock.unlock();
            }
        }

        @Override
        public String describe() {
            return "late RCX";
        }

        @Override
        public void close() {
        }

        private static byte[] concat(byte[] a, byte[] b) {
            byte[] out = java.util.Arrays.copyOf(a, a.length + b.length);
            System.arraycopy(b, 0, out, a.length, b.length);
            return out;
        }
    }

    private static RcxBrick brick(LateBrick line, boolean echo) throws IOException {
        Communicator c = new Communicator(line);
        c.open();
        RcxBrick brick = new RcxBrick("rcx-late", new BrickChannel("rcx-late", c, REPLY_TIMEOUT), echo);
        assertEquals(BATTERY, brick.batteryMillivolts(), "a prompt answer first (the channel's first exchange waits longer)");
        return brick;
    }

    /** Asks until the channel has reopened after a failed exchange; any other failure fails the test. */
    private static int batteryOnceReopened(RcxBrick brick) {
        int[] got = new int[1];
        Await.until("the channel reopens and the battery is read", Duration.ofSeconds(10), () -> {
            try {
                got[0] = brick.batteryMillivolts();
                return true;
            } catch (LinkLostException e) {
                if (e.getMessage().contains("next reopen attempt")) {
                    return false;
                }
                throw new AssertionError("a late answer was taken for the next request's: " + e.getMessage(), e);
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
        });
        return got[0];
    }

    @ParameterizedTest(name = "echoing tower: {0}")
    @ValueSource(booleans = {true, false})
    void aRequestAnsweredAfterBothAttemptsGaveUpDoesNotSpoilTheNextOne(boolean echo) throws Exception {
        LateBrick line = new LateBrick(echo);
        RcxBrick brick = brick(line, echo);
        line.delayNext(400, 400);
        assertThrows(LinkTimeoutException.class, brick::alive, "both attempts wait 150 ms, the answers take 400");
        assertEquals(BATTERY, batteryOnceReopened(brick), "the late echoes and replies of ALIVE are skipped");
        assertEquals(BATTERY, brick.batteryMillivolts(), "and the link goes on as before");
        brick.alive();
    }

    @ParameterizedTest(name = "echoing tower: {0}")
    @ValueSource(booleans = {true, false})
    void aFirstAttemptAnsweredDuringTheSecondLeavesNoStaleBytesBehind(boolean echo) throws Exception {
        LateBrick line = new LateBrick(echo);
        RcxBrick brick = brick(line, echo);
        // the first attempt's answer is due at 200 ms, after its 150 ms timeout; the second's at 210
        line.delayNext(200, 60);
        assertEquals(BATTERY, brick.batteryMillivolts(), "the second attempt takes the first one's answer (the same bytes)");
        assertEquals(BATTERY, brick.batteryMillivolts(), "the second attempt's own answer, still on the line, is skipped");
        brick.alive();
        assertEquals(BATTERY, brick.batteryMillivolts());
    }

    @ParameterizedTest(name = "echoing tower: {0}")
    @ValueSource(booleans = {true, false})
    void noiseWithNoRequestLateIsStillALostFraming(boolean echo) throws Exception {
        LateBrick line = new LateBrick(echo);
        RcxBrick brick = brick(line, echo);
        line.noise((byte) 0x55, (byte) 0x00, (byte) 0x12);
        LinkLostException lost = assertThrows(LinkLostException.class, brick::batteryMillivolts);
        assertTrue(lost.getMessage().contains("framing") || lost.getMessage().contains("garbled"), lost.getMessage());
        assertTrue(lost.getMessage().contains("late RCX"), "names the link: " + lost.getMessage());
    }
}
