package io.robomw.platform.rcx;

import io.robomw.testkit.Await;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.LinkTimeoutException;
import io.robomw.platform.testkit.Answer;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.time.Duration;
import java.util.Arrays;
import java.util.Deque;
import java.util.concurrent.ConcurrentLinkedDeque;

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

    /** How late the brick answers the next packets, in order; 5 ms for a packet with none queued. */
    private final Deque<Long> delaysMillis = new ConcurrentLinkedDeque<>();

    private void delayNext(long... millis) {
        for (long m : millis) {
            delaysMillis.add(m);
        }
    }

    /**
     * A tower and brick that answer each packet written with its echo (if the tower echoes) and
     * the reply, after the delay the test queued for that packet. Bytes come out in the order they
     * are due; closing and reopening keeps them, as a serial port's input buffer does.
     */
    private ScriptedLink line(boolean echo) {
        return new ScriptedLink().named("late RCX").answeringWith(packet -> {
            int op = RcxPacket.decode(packet).opcode();
            byte[] data = new byte[RcxPacket.replyDataLength(op)];
            if (data.length == 2) {
                data[0] = (byte) BATTERY;
                data[1] = (byte) (BATTERY >> 8);
            }
            byte[] reply = RcxPacket.encode(RcxPacket.replyOpcode(op), data);
            Long delay = delaysMillis.poll();
            byte[] answer = reply;
            if (echo) {
                answer = Arrays.copyOf(packet, packet.length + reply.length);
                System.arraycopy(reply, 0, answer, packet.length, reply.length);
            }
            return Answer.of(answer).after(Duration.ofMillis(delay == null ? 5 : delay));
        });
    }

    private static RcxBrick brick(ScriptedLink line, boolean echo) throws IOException {
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
        ScriptedLink line = line(echo);
        RcxBrick brick = brick(line, echo);
        delayNext(400, 400);
        assertThrows(LinkTimeoutException.class, brick::alive, "both attempts wait 150 ms, the answers take 400");
        assertEquals(BATTERY, batteryOnceReopened(brick), "the late echoes and replies of ALIVE are skipped");
        assertEquals(BATTERY, brick.batteryMillivolts(), "and the link goes on as before");
        brick.alive();
    }

    @ParameterizedTest(name = "echoing tower: {0}")
    @ValueSource(booleans = {true, false})
    void aFirstAttemptAnsweredDuringTheSecondLeavesNoStaleBytesBehind(boolean echo) throws Exception {
        ScriptedLink line = line(echo);
        RcxBrick brick = brick(line, echo);
        // the first attempt's answer is due at 200 ms, after its 150 ms timeout; the second's at 210
        delayNext(200, 60);
        assertEquals(BATTERY, brick.batteryMillivolts(), "the second attempt takes the first one's answer (the same bytes)");
        assertEquals(BATTERY, brick.batteryMillivolts(), "the second attempt's own answer, still on the line, is skipped");
        brick.alive();
        assertEquals(BATTERY, brick.batteryMillivolts());
    }

    @ParameterizedTest(name = "echoing tower: {0}")
    @ValueSource(booleans = {true, false})
    void noiseWithNoRequestLateIsStillALostFraming(boolean echo) throws Exception {
        ScriptedLink line = line(echo);
        RcxBrick brick = brick(line, echo);
        line.deliver(new byte[] {0x55, 0x00, 0x12}); // noise on the line
        LinkLostException lost = assertThrows(LinkLostException.class, brick::batteryMillivolts);
        assertTrue(lost.getMessage().contains("framing") || lost.getMessage().contains("garbled"), lost.getMessage());
        assertTrue(lost.getMessage().contains("late RCX"), "names the link: " + lost.getMessage());
    }
}
