package io.robomw.platform.nxt;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import org.junit.jupiter.api.Test;

import java.io.ByteArrayOutputStream;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Pipelined telegrams against a hand-written brick that answers each telegram of a write in order:
 * one round trip for a whole batch, never more than one of the brick's 128-byte Bluetooth receive
 * buffers in a write, and the framing kept when the brick refuses one of them.
 */
class NxtBrickPipelineTest {

    /** Answers every telegram a write carries, in order; refuses SETOUTPUTSTATE on port 2 with 0xC0. */
    static final class AnsweringBrick implements Link {
        final List<Integer> writes = new ArrayList<>();
        private final Deque<Byte> replies = new ArrayDeque<>();
        private boolean open;

        @Override
        public void open() {
            open = true;
        }

        @Override
        public boolean isOpen() {
            return open;
        }

        @Override
        public void write(byte[] data, int off, int len) {
            writes.add(len);
            int at = off;
            while (at < off + len) {
                int length = (data[at] & 0xFF) | (data[at + 1] & 0xFF) << 8;
                byte[] telegram = java.util.Arrays.copyOfRange(data, at + 2, at + 2 + length);
                answer(telegram);
                at += 2 + length;
            }
        }

        private void answer(byte[] t) {
            int op = t[1] & 0xFF;
            boolean refuse = op == NxtTelegram.SETOUTPUTSTATE && t[2] == 2;
            int length = op == NxtTelegram.GETOUTPUTSTATE ? NxtTelegram.GETOUTPUTSTATE_REPLY : NxtTelegram.STATUS_REPLY;
            ByteArrayOutputStream reply = new ByteArrayOutputStream();
            reply.write(length);
            reply.write(0);
            reply.write(NxtTelegram.REPLY);
            reply.write(op);
            reply.write(refuse ? NxtStatus.OUT_OF_RANGE : NxtStatus.SUCCESS);
            for (int i = 3; i < length; i++) {
                reply.write(i == 3 ? t[2] : 0);
            }
            for (byte b : reply.toByteArray()) {
                replies.add(b);
            }
        }

        @Override
        public int read(byte[] buf, int off, int len, Duration timeout) {
            int n = 0;
            while (n < len && !replies.isEmpty()) {
                buf[off + n++] = replies.poll();
            }
            return n;
        }

        @Override
        public String describe() {
            return "answering brick";
        }

        @Override
        public void close() {
            open = false;
        }
    }

    private final AnsweringBrick link = new AnsweringBrick();
    private final NxtBrick brick = brick(link);

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
        int total = link.writes.stream().mapToInt(Integer::intValue).sum();
        assertEquals(6 * (14 + 5), total, "every telegram went out, with its length prefix");
        assertTrue(link.writes.stream().allMatch(n -> n <= NxtBrick.PIPELINE_BYTES), "no write beyond 128 bytes: " + link.writes);
        assertEquals(1 + (total - 1) / NxtBrick.PIPELINE_BYTES, link.writes.size(), "as few writes as fit: " + link.writes);
    }

    @Test
    void shouldNameTheRefusedCommandAndKeepTheFramingForTheNextExchange() throws Exception {
        NxtException e = assertThrows(NxtException.class, () -> brick.requestAll(List.of(setOutput(0), setOutput(2), poll(0))));
        assertTrue(e.getMessage().contains("SETOUTPUTSTATE on port 2"), e.getMessage());

        byte[] next = brick.requestAllowing(NxtTelegram.getOutputState(1), NxtTelegram.GETOUTPUTSTATE_REPLY, 1);
        assertEquals(NxtTelegram.GETOUTPUTSTATE, next[1], "every reply of the refused batch was read: the next exchange is in step");
        assertEquals(1, next[3]);
    }
}
