package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Deadline;
import io.robomw.platform.link.LinkLostException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.concurrent.atomic.AtomicLong;

/**
 * One EV3 brick behind a {@link BrickChannel}: numbers each direct command with the next message
 * counter, sends it, and reads replies by their length field, never by timing, until the one
 * carrying that counter arrives. A reply with another counter is a late answer to an earlier
 * request (one that timed out) and is skipped; a length or type no reply can have means the link
 * lost its framing and is reported as a lost link (the channel reopens it).
 * {@code DIRECT_REPLY_ERROR} becomes an {@link Ev3Exception} naming the instructions, ports and
 * counter.
 *
 * <p>Thread-safe: the channel runs one exchange at a time, and the counter is only touched inside
 * an exchange.
 */
public final class Ev3Brick {

    private static final Logger LOG = LoggerFactory.getLogger(Ev3Brick.class);

    /** The first message counter, as ev3-dc starts, so wire logs compare with its traces. */
    public static final int FIRST_COUNTER = 0x2A;

    private final String robot;
    private final BrickChannel channel;
    private final AtomicLong skippedReplies = new AtomicLong();
    private int nextCounter = FIRST_COUNTER;

    /**
     * @param robot   the robot's name, for messages
     * @param channel the channel to the brick
     */
    public Ev3Brick(String robot, BrickChannel channel) {
        this.robot = robot;
        this.channel = channel;
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /**
     * Sends a command that wants a reply and waits for its reply.
     *
     * @param command a command built with {@link Ev3Command#withReply(int)}
     * @return its reply, {@link Ev3Reply#isOk() ok}, carrying exactly the command's globals
     * @throws IOException   if the link failed, lost its framing, or the reply did not come in time
     * @throws Ev3Exception  if the brick answered {@code DIRECT_REPLY_ERROR}
     */
    public Ev3Reply request(Ev3Command command) throws IOException {
        if (!command.replyWanted()) {
            throw new IllegalArgumentException("request() waits for a reply, but " + command + " asks for none; use send()");
        }
        return channel.exchange((c, timeout) -> exchange(c, timeout, command));
    }

    /**
     * Sends a command that wants no reply; returns once it is written.
     *
     * @param command a command built with {@link Ev3Command#withoutReply()}
     * @throws IOException if the link failed
     */
    public void send(Ev3Command command) throws IOException {
        if (command.replyWanted()) {
            throw new IllegalArgumentException("send() does not read a reply, but " + command + " asks for one; use request()");
        }
        channel.exchange((c, timeout) -> exchange(c, timeout, command));
    }

    private Ev3Reply exchange(Communicator c, Duration timeout, Ev3Command command) throws IOException {
        int counter = nextCounter;
        nextCounter = (nextCounter + 1) & 0xFFFF;
        c.send(command.encode(counter));
        if (!command.replyWanted()) {
            return null;
        }
        Deadline deadline = Deadline.after(timeout);
        while (true) {
            byte[] lengthField = c.receiveExactly(Ev3Frame.LENGTH_FIELD_SIZE, deadline.remaining());
            int length = LittleEndian.u16(lengthField, 0);
            if (length < Ev3Frame.MIN_REPLY_LENGTH || length > Ev3Frame.MAX_REPLY_LENGTH) {
                throw new LinkLostException(channel.describe(), "the EV3 reply to direct command #" + counter + " announced " + length
                        + " bytes after its length field, but a reply has " + Ev3Frame.MIN_REPLY_LENGTH + ".." + Ev3Frame.MAX_REPLY_LENGTH
                        + "; the link lost its framing");
            }
            byte[] frame = new byte[Ev3Frame.LENGTH_FIELD_SIZE + length];
            System.arraycopy(lengthField, 0, frame, 0, Ev3Frame.LENGTH_FIELD_SIZE);
            byte[] rest = c.receiveExactly(length, deadline.remaining());
            System.arraycopy(rest, 0, frame, Ev3Frame.LENGTH_FIELD_SIZE, length);
            int type = Ev3Frame.type(frame);
            if (type != Ev3Frame.DIRECT_REPLY && type != Ev3Frame.DIRECT_REPLY_ERROR) {
                throw new LinkLostException(channel.describe(), String.format("expected a direct reply to command #%d, got %s; the link lost its framing",
                        counter, Ev3Frame.typeName(type)));
            }
            Ev3Reply reply = Ev3Reply.decode(frame);
            if (reply.counter() != counter) {
                long n = skippedReplies.incrementAndGet();
                LOG.debug("robot '{}': skipped a late EV3 reply #{} while waiting for #{} ({} skipped so far)", robot, reply.counter(), counter, n);
                continue;
            }
            if (!reply.isOk()) {
                throw new Ev3Exception(robot, command, counter);
            }
            if (reply.globals().length != command.globals()) {
                throw new LinkLostException(channel.describe(), "the EV3 reply to direct command #" + counter + " carries "
                        + reply.globals().length + " global bytes, but the command reserved " + command.globals());
            }
            return reply;
        }
    }


    /** @return replies skipped because they carried another message counter (late answers) */
    public long skippedReplies() {
        return skippedReplies.get();
    }

    /**
     * @return the battery voltage, volts
     * @throws IOException if the link failed
     */
    public double batteryVolts() throws IOException {
        return request(Ev3Command.withReply(4).uiReadVbatt(0).build()).dataF(0);
    }

    /**
     * Plays a tone; returns at once (the brick plays it on its own).
     *
     * @param volume 0..100
     * @param hertz  frequency
     * @param millis duration
     * @throws IOException if the link failed
     */
    public void playTone(int volume, int hertz, int millis) throws IOException {
        request(Ev3Command.withReply(0).soundTone(volume, hertz, millis).build());
    }
}
