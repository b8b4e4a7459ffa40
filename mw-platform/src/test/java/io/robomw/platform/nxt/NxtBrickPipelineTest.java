package io.robomw.platform.nxt;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.LinkTimeoutException;
import io.robomw.platform.testkit.Framing;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.io.ByteArrayOutputStream;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Pipelined telegrams against a scripted brick that answers each telegram of a write in order:
 * one round trip for a whole batch, never more than one of the brick's 128-byte Bluetooth receive
 * buffers in a write, and the framing kept when the brick refuses one of them.
 */
class NxtBrickPipelineTest {

    /** A brick that answers every telegram a write carries, in order; it refuses SETOUTPUTSTATE on port 2 with 0xC0. */
    private static byte[] answer(byte[] frame) {
        byte[] t = java.util.Arrays.copyOfRange(frame, 2, frame.length);
        int op = t[1] & 0xFF;
        boolean refuse = op == NxtTelegram.SETOUTPUTSTATE && t[2] == 2;
        int length = op == NxtTelegram.GETOUTPUTSTATE ? NxtTelegram.GETOUTPUTSTATE_REPLY
                : op == NxtTelegram.GETINPUTVALUES ? NxtTelegram.GETINPUTVALUES_REPLY : NxtTelegram.STATUS_REPLY;
        ByteArrayOutputStream reply = new ByteArrayOutputStream();
        reply.write(length);
        reply.write(0);
        reply.write(NxtTelegram.REPLY);
        reply.write(op);
        reply.write(refuse ? NxtStatus.OUT_OF_RANGE : NxtStatus.SUCCESS);
        for (int i = 3; i < length; i++) {
            reply.write(i == 3 ? t[2] : 0);
        }
        return reply.toByteArray();
    }

    private final ScriptedLink link = new ScriptedLink().named("answering brick")
            .framedBy(Framing.lengthPrefixed16LittleEndian()).answering(NxtBrickPipelineTest::answer);
    private final NxtBrick brick = brick(link);

    /** @return the length of each write, in order */
    private List<Integer> writes() {
        return link.eachWrite().stream().map(w -> w.length).toList();
    }

    private static NxtBrick brick(Link link) {
        Communicator c = new Communicator(link);
        try {
            c.open();
        } catch (java.io.IOException e) {
            throw new IllegalStateException(e);
        }
        return new NxtBrick("nxt-test", new BrickChannel("nxt-test", c, Duration.ofMillis(200)));
    }

    private static NxtBrick.Request setOutput(int port) {
        return new NxtBrick.Request(NxtTelegram.setOutputState(true, OutputState.running(port, 50, OutputState.Regulation.SPEED, 360)),
                NxtTelegram.STATUS_REPLY, port);
    }

    private static NxtBrick.Request poll(int port) {
        return new NxtBrick.Request(NxtTelegram.getOutputState(port), NxtTelegram.GETOUTPUTSTATE_REPLY, port);
    }

    @Test
    void shouldSendABatchInWritesOfAtMostOneBluetoothBufferAndReadEveryReplyInOrder() throws Exception {
        List<NxtBrick.Request> batch = new ArrayList<>();
        for (int i = 0; i < 6; i++) {
            batch.add(setOutput(i % 2));
            batch.add(poll(i % 2));
        }

        List<byte[]> replies = brick.pipeline(batch);

        assertEquals(12, replies.size());
        for (int i = 0; i < 12; i++) {
            assertEquals(batch.get(i).telegram()[1], replies.get(i)[1], "reply " + i + " answers telegram " + i);
        }
        List<Integer> writes = writes();
        int total = writes.stream().mapToInt(Integer::intValue).sum();
        assertEquals(6 * (14 + 5), total, "every telegram went out, with its length prefix");
        assertTrue(writes.stream().allMatch(n -> n <= NxtBrick.PIPELINE_BYTES), "no write beyond 128 bytes: " + writes);
        assertEquals(1 + (total - 1) / NxtBrick.PIPELINE_BYTES, writes.size(), "as few writes as fit: " + writes);
        for (byte[] write : link.eachWrite()) {
            int at = 0;
            while (at < write.length) {
                at += 2 + ((write[at] & 0xFF) | (write[at + 1] & 0xFF) << 8);
            }
            assertEquals(write.length, at, "a write carries whole telegrams");
        }
    }

    @Test
    void shouldNameTheRefusedCommandAndKeepTheFramingForTheNextExchange() throws Exception {
        NxtException e = assertThrows(NxtException.class, () -> brick.requestAll(List.of(setOutput(0), setOutput(2), poll(0))));
        assertTrue(e.getMessage().contains("SETOUTPUTSTATE on port 2"), e.getMessage());

        byte[] next = brick.requestAllowing(NxtTelegram.getOutputState(1), NxtTelegram.GETOUTPUTSTATE_REPLY, 1);
        assertEquals(NxtTelegram.GETOUTPUTSTATE, next[1], "every reply of the refused batch was read: the next exchange is in step");
        assertEquals(1, next[3]);
    }

    /**
     * A Bluetooth link's latency spike: the brick's reply to a poll comes after the poll's timeout,
     * ahead of the reply to the next request. It is dropped as late, and the next request gets its
     * own reply, instead of the link being declared lost ("the link lost its framing") for it.
     */
    @Test
    void aReplyThatCameAfterItsTimeoutIsDroppedAndTheNextRequestGetsItsOwn() throws Exception {
        boolean[] silent = {false};
        ScriptedLink slow = new ScriptedLink().named("slow brick").framedBy(Framing.lengthPrefixed16LittleEndian())
                .answering(frame -> silent[0] ? null : answer(frame));
        NxtBrick brick = brick(slow);
        brick.request(setOutput(0).telegram(), NxtTelegram.STATUS_REPLY, 0); // the channel has answered: the 200 ms timeout holds from now

        silent[0] = true;
        assertThrows(LinkTimeoutException.class, () -> brick.requestAllowing(NxtTelegram.getOutputState(1), NxtTelegram.GETOUTPUTSTATE_REPLY, 1));
        silent[0] = false;
        byte[] poll = NxtTelegram.getOutputState(1);
        slow.deliver(answer(withLengthPrefix(poll))); // the poll's reply, late

        byte[] reply = brick.requestAllowing(NxtTelegram.getInputValues(0), NxtTelegram.GETINPUTVALUES_REPLY, 0);
        assertEquals(NxtTelegram.GETINPUTVALUES, reply[1], "the request got its own reply");

        slow.deliver(answer(withLengthPrefix(poll))); // a reply nobody is owed: the stream is out of step
        LinkLostException lost = assertThrows(LinkLostException.class, () -> brick.requestAllowing(NxtTelegram.getInputValues(0),
                NxtTelegram.GETINPUTVALUES_REPLY, 0));
        assertTrue(lost.getMessage().contains("lost its framing"), lost.getMessage());
    }

    private static byte[] withLengthPrefix(byte[] telegram) {
        return NxtTelegram.withLengthPrefix(telegram);
    }
}
