package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.LinkLostException;

import java.io.IOException;

/**
 * One NXT brick behind a {@link BrickChannel}: sends telegrams with their length prefix and reads
 * each reply by its length prefix, never by timing. A reply of the wrong type or opcode means the
 * link lost its framing and is reported as a lost link (the channel reopens it); a status other
 * than success becomes an {@link NxtException} naming the command, port and status.
 *
 * <p>Thread-safe (the channel serialises exchanges).
 */
public final class NxtBrick {

    private final String robot;
    private final BrickChannel channel;

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
        byte[] reply = requestAllowing(telegram, replyLength, port);
        int status = reply[NxtTelegram.STATUS_OFFSET] & 0xFF;
        if (status != NxtStatus.SUCCESS) {
            throw new NxtException(robot, telegram[1] & 0xFF, port, status, telegram);
        }
        return reply;
    }

    /**
     * Sends several telegrams back to back, then reads their replies in order: motors started in
     * one batch start within a few bytes' time of each other, not a round trip apart.
     *
     * @param telegrams   telegrams that each want a status-only reply
     * @param ports       the port of each, for messages
     * @throws IOException if the link failed or lost its framing
     * @throws NxtException naming the first command the brick refused
     */
    public void requestAll(java.util.List<byte[]> telegrams, int[] ports) throws IOException {
        int[] statuses = channel.exchange((c, timeout) -> {
            java.io.ByteArrayOutputStream out = new java.io.ByteArrayOutputStream();
            for (byte[] t : telegrams) {
                out.writeBytes(NxtTelegram.withLengthPrefix(t));
            }
            c.send(out.toByteArray());
            int[] result = new int[telegrams.size()];
            for (int i = 0; i < telegrams.size(); i++) {
                int opcode = telegrams.get(i)[1] & 0xFF;
                byte[] prefix = c.receiveExactly(2, timeout);
                int length = LittleEndian.u16(prefix, 0);
                if (length != NxtTelegram.STATUS_REPLY) {
                    throw new LinkLostException(channel.describe(), "NXT reply to " + NxtTelegram.name(opcode) + " announced " + length
                            + " bytes, expected " + NxtTelegram.STATUS_REPLY + "; the link lost its framing");
                }
                byte[] reply = c.receiveExactly(length, timeout);
                if ((reply[0] & 0xFF) != NxtTelegram.REPLY || (reply[1] & 0xFF) != opcode) {
                    throw new LinkLostException(channel.describe(), "expected a reply to " + NxtTelegram.name(opcode) + "; the link lost its framing");
                }
                result[i] = reply[NxtTelegram.STATUS_OFFSET] & 0xFF;
            }
            return result;
        });
        for (int i = 0; i < statuses.length; i++) {
            if (statuses[i] != NxtStatus.SUCCESS) {
                throw new NxtException(robot, telegrams.get(i)[1] & 0xFF, ports[i], statuses[i], telegrams.get(i));
            }
        }
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
        int opcode = telegram[1] & 0xFF;
        return channel.exchange((c, timeout) -> {
            c.send(NxtTelegram.withLengthPrefix(telegram));
            byte[] prefix = c.receiveExactly(2, timeout);
            int length = LittleEndian.u16(prefix, 0);
            if (length < NxtTelegram.STATUS_REPLY || length > NxtTelegram.MAX_LENGTH) {
                throw new LinkLostException(channel.describe(), "NXT reply to " + NxtTelegram.name(opcode) + " announced " + length
                        + " bytes; the link lost its framing");
            }
            byte[] reply = c.receiveExactly(length, timeout);
            if ((reply[0] & 0xFF) != NxtTelegram.REPLY || (reply[1] & 0xFF) != opcode) {
                throw new LinkLostException(channel.describe(), String.format("expected a reply to %s, got %02X %02X; the link lost its framing",
                        NxtTelegram.name(opcode), reply[0] & 0xFF, reply[1] & 0xFF));
            }
            int status = reply[NxtTelegram.STATUS_OFFSET] & 0xFF;
            if (status == NxtStatus.SUCCESS && length != replyLength) {
                throw new LinkLostException(channel.describe(), NxtTelegram.name(opcode) + " reply is " + length + " bytes, expected " + replyLength);
            }
            return reply;
        });
    }

    /**
     * @return the battery voltage, millivolts
     * @throws IOException if the link failed
     */
    public int batteryMillivolts() throws IOException {
        return LittleEndian.u16(request(NxtTelegram.getBatteryLevel(), NxtTelegram.GETBATTERYLEVEL_REPLY, -1), 3);
    }

    /**
     * Keeps the brick from sleeping.
     *
     * @return its sleep time limit, milliseconds
     * @throws IOException if the link failed
     */
    public long keepAlive() throws IOException {
        return LittleEndian.u32(request(NxtTelegram.keepAlive(), NxtTelegram.KEEPALIVE_REPLY, -1), 3);
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
