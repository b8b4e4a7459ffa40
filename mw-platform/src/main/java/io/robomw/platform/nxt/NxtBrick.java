package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.brick.RoundTripEstimate;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.LinkTimeoutException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;

/**
 * One NXT brick behind a {@link BrickChannel}: sends telegrams with their length prefix and reads
 * each reply by its length prefix, never by timing. A reply of the wrong type or opcode means the
 * link lost its framing and is reported as a lost link (the channel reopens it), but for a late
 * one: after a request whose reply did not come within the timeout (a Bluetooth link's latency
 * spike, a busy host), that reply may still come, whole, before the next one; a well-formed reply
 * to another command is then taken for it and dropped, once for each reply owed. A status other
 * than success becomes an {@link NxtException} naming the command, port and status.
 *
 * <p>Thread-safe (the channel serialises exchanges).
 */
public final class NxtBrick {

    private static final Logger LOG = LoggerFactory.getLogger(NxtBrick.class);

    private final String robot;
    private final BrickChannel channel;
    private final RoundTripEstimate roundTrip = new RoundTripEstimate();
    /**
     * Replies that did not come within their timeout and may still come; only touched inside the
     * channel's exchanges. Kept across a reopen of the link: a serial port's input (a USB or
     * Bluetooth serial device) survives a close and an open, so a late reply can still come after
     * it; over a reopened TCP link none can, and only a well-formed reply to another command is
     * ever dropped on this count.
     */
    private int owed;

    /**
     * @param robot   the robot's name, for messages
     * @param channel the channel to the brick
     */
    public NxtBrick(String robot, BrickChannel channel) {
        this.robot = robot;
        this.channel = channel;
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return how long until the exchange under way on the channel is expected to end, nanoseconds */
    public long nanosUntilFree() {
        return channel.nanosUntilFree();
    }

    /** @return the link's measured round trip, request sent to reply received */
    public RoundTripEstimate roundTrip() {
        return roundTrip;
    }

    /**
     * Sends a telegram that wants no reply.
     *
     * @param telegram the telegram (type 0x80)
     * @throws IOException if the link failed
     */
    public void send(byte[] telegram) throws IOException {
        channel.exchange((c, timeout) -> {
            c.send(NxtTelegram.withLengthPrefix(telegram));
            return null;
        });
    }

    /**
     * Sends a telegram and returns its reply if the status is success.
     *
     * @param telegram    the telegram (type 0x00)
     * @param replyLength the reply's length without prefix
     * @param port        the port it is for, for messages, or -1
     * @return the reply, starting with {@code 02 opcode status}
     * @throws IOException if the link failed or lost its framing
     * @throws NxtException if the brick answered with an error status
     */
    public byte[] request(byte[] telegram, int replyLength, int port) throws IOException {
        Request request = new Request(telegram, replyLength, port);
        byte[] reply = requestAllowing(request);
        checkStatus(request, reply);
        return reply;
    }

    /**
     * @param request a telegram sent
     * @param reply   its reply
     * @throws NxtException naming the robot, the command, the port, the status and the telegram, if
     *                      the status is not success
     */
    public void checkStatus(Request request, byte[] reply) {
        int status = NxtTelegram.status(reply);
        if (status != NxtStatus.SUCCESS) {
            throw new NxtException(robot, NxtTelegram.opcode(request.telegram()), request.port(), status, request.telegram());
        }
    }

    /**
     * Checks every reply of a pipelined batch, in order.
     *
     * @param requests the telegrams sent
     * @param replies  their replies, as many
     * @throws NxtException naming the first command the brick refused
     */
    public void checkStatus(java.util.List<Request> requests, java.util.List<byte[]> replies) {
        for (int i = 0; i < replies.size(); i++) {
            checkStatus(requests.get(i), replies.get(i));
        }
    }

    /**
     * Decodes a successful GETOUTPUTSTATE reply; a reply carrying a code the firmware does not have
     * means the link lost its framing.
     *
     * @param reply the reply
     * @return what it reports
     * @throws LinkLostException naming the link, if the reply does not decode
     */
    public NxtTelegram.OutputReading outputReading(byte[] reply) throws LinkLostException {
        try {
            return NxtTelegram.outputReading(reply);
        } catch (IllegalArgumentException e) {
            throw new LinkLostException(channel.describe(), e.getMessage() + "; the link lost its framing", e);
        }
    }

    /**
     * One telegram of a {@link #pipeline pipelined} batch.
     *
     * @param telegram    the telegram, without its length prefix, asking for a reply (type 0x00)
     * @param replyLength the length of its reply when the brick accepts it, without prefix
     * @param port        the port it is for, for messages, or -1
     */
    public record Request(byte[] telegram, int replyLength, int port) {
    }

    /**
     * Sends telegrams back to back and then reads their replies, in order. Over a link with
     * latency this costs one round trip for the whole batch instead of one per telegram, and
     * motors started in one batch start within a millisecond of each other (the firmware takes one
     * telegram from its Bluetooth buffer per 1 ms tick). A batch goes out in writes of at most
     * {@value #PIPELINE_BYTES} bytes, each followed by its replies, so it never overruns the
     * brick's Bluetooth receive buffer ({@code d_bt.r}: two buffers of 128 bytes).
     *
     * @param requests the telegrams
     * @return the replies, in the same order, starting with {@code 02 opcode status}, whatever their status
     * @throws IOException if the link failed or lost its framing
     */
    public java.util.List<byte[]> pipeline(java.util.List<Request> requests) throws IOException {
        return channel.exchange((c, timeout) -> {
            java.util.List<byte[]> replies = new java.util.ArrayList<>(requests.size());
            int next = 0;
            while (next < requests.size()) {
                java.io.ByteArrayOutputStream out = new java.io.ByteArrayOutputStream();
                int first = next;
                while (next < requests.size() && (next == first
                        || out.size() + requests.get(next).telegram().length + 2 <= PIPELINE_BYTES)) {
                    out.writeBytes(NxtTelegram.withLengthPrefix(requests.get(next).telegram()));
                    next++;
                }
                long sent = BrickChannel.LINK_TIME.nanoTime();
                c.send(out.toByteArray());
                for (int i = first; i < next; i++) {
                    try {
                        replies.add(readReply(c, timeout, requests.get(i)));
                    } catch (LinkTimeoutException e) {
                        owe(next - i);
                        throw e;
                    }
                    if (i == first) {
                        roundTrip.sample(BrickChannel.LINK_TIME.nanoTime() - sent);
                    }
                }
            }
            return replies;
        });
    }

    /** The most bytes one write of a pipelined batch carries: one of the NXT's Bluetooth receive buffers. */
    public static final int PIPELINE_BYTES = 128;

    /** At most this many late replies are looked out for (a pipelined batch's worth); more owed than that were lost. */
    static final int MAX_OWED = 16;

    private void owe(int replies) {
        owed = Math.min(MAX_OWED, owed + replies);
    }

    private byte[] readReply(io.robomw.platform.link.Communicator c, java.time.Duration timeout, Request request) throws IOException {
        int opcode = NxtTelegram.opcode(request.telegram());
        while (true) {
            byte[] prefix = c.receiveExactly(2, timeout);
            int length = LittleEndian.u16(prefix, 0);
            if (length < NxtTelegram.STATUS_REPLY || length > NxtTelegram.MAX_LENGTH) {
                throw new LinkLostException(channel.describe(), "NXT reply to " + NxtTelegram.name(opcode) + " announced " + length
                        + " bytes; the link lost its framing");
            }
            byte[] reply = c.receiveExactly(length, timeout);
            boolean isReply = (reply[NxtTelegram.TYPE_OFFSET] & 0xFF) == NxtTelegram.REPLY;
            if (isReply && NxtTelegram.opcode(reply) == opcode) {
                return checkedLength(request, opcode, length, reply);
            }
            if (isReply && owed > 0) {
                owed--;
                LOG.debug("robot '{}': dropped a late reply to {} on {} while waiting for the reply to {} ({} more may come)", robot,
                        NxtTelegram.name(NxtTelegram.opcode(reply)), channel.describe(), NxtTelegram.name(opcode), owed);
                continue;
            }
            throw new LinkLostException(channel.describe(), String.format("expected a reply to %s, got %02X %02X; the link lost its framing",
                    NxtTelegram.name(opcode), reply[NxtTelegram.TYPE_OFFSET] & 0xFF, NxtTelegram.opcode(reply)));
        }
    }

    private byte[] checkedLength(Request request, int opcode, int length, byte[] reply) throws LinkLostException {
        if (NxtTelegram.status(reply) == NxtStatus.SUCCESS && length != request.replyLength()) {
            throw new LinkLostException(channel.describe(), NxtTelegram.name(opcode) + " reply is " + length + " bytes, expected " + request.replyLength());
        }
        return reply;
    }

    /**
     * {@link #pipeline Pipelines} telegrams and checks every status.
     *
     * @param requests the telegrams
     * @return their replies
     * @throws IOException if the link failed or lost its framing
     * @throws NxtException naming the first command the brick refused (all replies were read)
     */
    public java.util.List<byte[]> requestAll(java.util.List<Request> requests) throws IOException {
        java.util.List<byte[]> replies = pipeline(requests);
        checkStatus(requests, replies);
        return replies;
    }

    /**
     * Like {@link #request}, but returns replies whatever their status (for commands whose status
     * says "not yet", such as LSGETSTATUS's pending).
     *
     * @param telegram    the telegram
     * @param replyLength the reply's length
     * @param port        the port, for messages
     * @return the reply
     * @throws IOException if the link failed or lost its framing
     */
    public byte[] requestAllowing(byte[] telegram, int replyLength, int port) throws IOException {
        return requestAllowing(new Request(telegram, replyLength, port));
    }

    private byte[] requestAllowing(Request request) throws IOException {
        return channel.exchange((c, timeout) -> {
            long sent = BrickChannel.LINK_TIME.nanoTime();
            c.send(NxtTelegram.withLengthPrefix(request.telegram()));
            byte[] reply;
            try {
                reply = readReply(c, timeout, request);
            } catch (LinkTimeoutException e) {
                owe(1);
                throw e;
            }
            roundTrip.sample(BrickChannel.LINK_TIME.nanoTime() - sent);
            return reply;
        });
    }

    /**
     * @return the battery voltage, millivolts
     * @throws IOException if the link failed
     */
    public int batteryMillivolts() throws IOException {
        return LittleEndian.u16(request(NxtTelegram.getBatteryLevel(), NxtTelegram.GETBATTERYLEVEL_REPLY, -1),
                NxtTelegram.DATA_OFFSET + NxtTelegram.BATTERY_MILLIVOLTS);
    }

    /**
     * Keeps the brick from sleeping.
     *
     * @return its sleep time limit, milliseconds
     * @throws IOException if the link failed
     */
    public long keepAlive() throws IOException {
        return LittleEndian.u32(request(NxtTelegram.keepAlive(), NxtTelegram.KEEPALIVE_REPLY, -1),
                NxtTelegram.DATA_OFFSET + NxtTelegram.SLEEP_LIMIT_MILLIS);
    }

    /**
     * @param hertz  frequency
     * @param millis duration
     * @throws IOException if the link failed
     */
    public void playTone(int hertz, int millis) throws IOException {
        request(NxtTelegram.playTone(true, hertz, millis), NxtTelegram.STATUS_REPLY, -1);
    }
}
