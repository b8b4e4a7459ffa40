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
 * <p>A request that timed out may still be answered: the tower's echo and the brick's reply come
 * late, after the next request was sent (a busy host, a slow IR line). The brick keeps count of
 * the bytes such late answers can still bring, and while that count is not spent it skips stale
 * bytes before the echo or the reply it waits for, instead of taking them for it (which would
 * mark a good link lost). Otherwise a wrong echo, header, complement, checksum or reply opcode
 * means the line lost its framing (IR noise) and is reported as a lost link; the channel reopens it.
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
    /** Bytes that answers to timed-out requests may still bring (echoes and replies), at most {@link #MAX_STALE}. */
    private int stale;

    /** The most stale bytes counted: the answers to a few timed-out requests. */
    static final int MAX_STALE = 4 * (RcxPacket.wireLength(5) + RcxPacket.wireLength(8));

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
                    stale = Math.min(MAX_STALE, stale + (echo ? packet.length : 0) + RcxPacket.wireLength(RcxPacket.replyDataLength(op)));
                    LOG.debug("robot '{}': no reply to {}; sending it again", robot, RcxPacket.name(op));
                }
            }
            throw silence;
        });
    }

    private RcxPacket.Decoded receive(Communicator c, Duration timeout, byte[] packet, int op) throws IOException {
        long deadline = BrickChannel.LINK_TIME.nanoTime() + timeout.toNanos();
        if (echo) {
            byte[] heard = readPast(c, packet, deadline);
            if (!Arrays.equals(heard, packet)) {
                throw new LinkLostException(channel.describe(), "the IR tower echoed " + RcxPacket.hex(heard) + " for "
                        + RcxPacket.hex(packet) + "; the line lost its framing");
            }
        }
        int replyData = RcxPacket.replyDataLength(op);
        int replyOpcode = RcxPacket.replyOpcode(op);
        byte[] start = readPast(c, new byte[]{RcxPacket.HEADER[0], RcxPacket.HEADER[1], RcxPacket.HEADER[2],
                (byte) replyOpcode, (byte) ~replyOpcode}, deadline);
        byte[] bytes = Arrays.copyOf(start, RcxPacket.wireLength(replyData));
        byte[] rest = c.receiveExactly(bytes.length - start.length, remaining(deadline));
        System.arraycopy(rest, 0, bytes, start.length, rest.length);
        RcxPacket.Decoded reply;
        try {
            reply = RcxPacket.decode(bytes);
        } catch (IllegalArgumentException e) {
            throw new LinkLostException(channel.describe(), "the RCX's reply to " + RcxPacket.name(op) + " is garbled: " + e.getMessage());
        }
        if (reply.opcode() != replyOpcode) {
            throw new LinkLostException(channel.describe(), String.format("expected the RCX's reply to %s (%02X), got opcode %02X; the line lost its framing",
                    RcxPacket.name(op), replyOpcode, reply.opcode()));
        }
        return reply;
    }

    /**
     * Reads as many bytes as {@code expected} has; while they differ from it and stale bytes may
     * still be coming, drops the oldest byte read and reads one more.
     *
     * @return the last bytes read: {@code expected}, or what came instead once no stale byte is left to skip
     */
    private byte[] readPast(Communicator c, byte[] expected, long deadline) throws IOException {
        byte[] window = c.receiveExactly(expected.length, remaining(deadline));
        int skipped = 0;
        while (!Arrays.equals(window, expected) && skipped < stale) {
            System.arraycopy(window, 1, window, 0, window.length - 1);
            window[window.length - 1] = c.receiveExactly(1, remaining(deadline))[0];
            skipped++;
        }
        if (skipped > 0) {
            stale -= skipped;
            LOG.debug("robot '{}': skipped {} stale bytes of an earlier request's late answer", robot, skipped);
        }
        return window;
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
