package io.robomw.platform.rcx;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.brick.RoundTripEstimate;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.LinkTimeoutException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.Arrays;

/**
 * One RCX behind its IR tower on a {@link BrickChannel}: one packet at a time (the infra-red link
 * is half-duplex, so nothing can be pipelined), each read back as the tower's echo (when the tower
 * echoes, as the serial one does) and then the brick's reply, whose length the request's opcode
 * fixes. Repeated opcodes get the toggle bit, so the brick does not take them for
 * retransmissions; a request whose reply does not come is sent once more, unchanged, as NQC does,
 * which the brick answers without running it twice.
 *
 * <p>A wrong echo, header, complement, checksum or reply opcode means the line lost its framing
 * (IR noise) and is reported as a lost link; the channel reopens it.
 *
 * <p>Thread-safe: the channel runs one exchange at a time; the toggle state is only touched inside
 * an exchange.
 */
public final class RcxBrick {

    private static final Logger LOG = LoggerFactory.getLogger(RcxBrick.class);

    /** Times a request is sent in all when its reply does not come. */
    static final int ATTEMPTS = 2;

    private final String robot;
    private final BrickChannel channel;
    private final boolean echo;
    private final RoundTripEstimate roundTrip = new RoundTripEstimate();
    private int lastOpcode = -1;

    /**
     * @param robot   the robot's name, for messages
     * @param channel the channel to the tower
     * @param echo    whether the tower echoes what it sends (the serial tower does, the USB one does not)
     */
    public RcxBrick(String robot, BrickChannel channel, boolean echo) {
        this.robot = robot;
        this.channel = channel;
        this.echo = echo;
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the measured round trip of a request and its reply */
    public RoundTripEstimate roundTrip() {
        return roundTrip;
    }

    /** @return how long until the exchange under way on the channel is expected to end, nanoseconds */
    public long nanosUntilFree() {
        return channel.nanosUntilFree();
    }

    /**
     * Sends a request and returns its reply.
     *
     * @param opcode the opcode, without the toggle bit
     * @param data   its data bytes
     * @return the reply
     * @throws IOException if the tower or brick did not answer, or the line lost its framing
     */
    public RcxPacket.Decoded request(int opcode, byte... data) throws IOException {
        if (RcxPacket.requestDataLength(opcode) != data.length) {
            throw new IllegalArgumentException(RcxPacket.name(opcode) + " takes " + RcxPacket.requestDataLength(opcode) + " data bytes, got " + data.length);
        }
        return channel.exchange((c, timeout) -> {
            int op = opcode == lastOpcode ? opcode | RcxPacket.TOGGLE : opcode;
            lastOpcode = op;
            byte[] packet = RcxPacket.encode(op, data);
            LinkTimeoutException silence = null;
            for (int attempt = 0; attempt < ATTEMPTS; attempt++) {
                long sent = BrickChannel.LINK_TIME.nanoTime();
                c.send(packet);
                try {
                    RcxPacket.Decoded reply = receive(c, timeout, packet, op);
                    roundTrip.sample(BrickChannel.LINK_TIME.nanoTime() - sent);
                    return reply;
                } catch (LinkTimeoutException e) {
                    silence = e;
                    LOG.debug("robot '{}': no reply to {}; sending it again", robot, RcxPacket.name(op));
                }
            }
            throw silence;
        });
    }

    private RcxPacket.Decoded receive(Communicator c, Duration timeout, byte[] packet, int op) throws IOException {
        long deadline = BrickChannel.LINK_TIME.nanoTime() + timeout.toNanos();
        if (echo) {
            byte[] heard = c.receiveExactly(packet.length, remaining(deadline));
            if (!Arrays.equals(heard, packet)) {
                throw new LinkLostException(channel.describe(), "the IR tower echoed " + RcxPacket.hex(heard) + " for "
                        + RcxPacket.hex(packet) + "; the line lost its framing");
            }
        }
        int replyData = RcxPacket.replyDataLength(op);
        byte[] bytes = c.receiveExactly(RcxPacket.wireLength(replyData), remaining(deadline));
        RcxPacket.Decoded reply;
        try {
            reply = RcxPacket.decode(bytes);
        } catch (IllegalArgumentException e) {
            throw new LinkLostException(channel.describe(), "the RCX's reply to " + RcxPacket.name(op) + " is garbled: " + e.getMessage());
        }
        if (reply.opcode() != RcxPacket.replyOpcode(op)) {
            throw new LinkLostException(channel.describe(), String.format("expected the RCX's reply to %s (%02X), got opcode %02X; the line lost its framing",
                    RcxPacket.name(op), RcxPacket.replyOpcode(op), reply.opcode()));
        }
        return reply;
    }

    private static Duration remaining(long deadline) {
        return Duration.ofNanos(Math.max(0, deadline - BrickChannel.LINK_TIME.nanoTime()));
    }

    /**
     * @return the battery voltage, millivolts
     * @throws IOException if the link failed
     */
    public int batteryMillivolts() throws IOException {
        return request(RcxPacket.GET_BATTERY).u16();
    }

    /**
     * @throws IOException if the brick does not answer
     */
    public void alive() throws IOException {
        request(RcxPacket.ALIVE);
    }
}
