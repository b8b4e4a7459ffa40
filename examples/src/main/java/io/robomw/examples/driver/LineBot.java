package io.robomw.examples.driver;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.brick.RoundTripEstimate;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Deadline;
import io.robomw.platform.link.LinkLostException;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;

/**
 * One LineBot behind a {@link BrickChannel}: a request line out, its reply line back, one exchange
 * at a time (the channel serialises the link agent's polls and program threads' sensor reads). A
 * reply is read to its LF, never by timing; one that does not parse means the link lost its
 * framing (a {@link LinkLostException}: the link agent reopens it); an {@code ERR} reply is the
 * board's refusal ({@link LineBotException}).
 *
 * <p>Thread-safe.
 */
public final class LineBot {

    private final String robot;
    private final BrickChannel channel;
    private final RoundTripEstimate roundTrip = new RoundTripEstimate();

    /**
     * @param robot   the robot's name, for messages
     * @param channel the channel to the board
     */
    public LineBot(String robot, BrickChannel channel) {
        this.robot = robot;
        this.channel = channel;
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the link's measured round trip */
    public RoundTripEstimate roundTrip() {
        return roundTrip;
    }

    /** @return how long until the exchange under way on the channel is expected to end, nanoseconds */
    public long nanosUntilFree() {
        return channel.nanosUntilFree();
    }

    /**
     * Sends a request and reads its reply.
     *
     * @param request the request, without its LF
     * @return the reply, without its LF
     * @throws IOException       if the link failed, or the reply did not come or does not parse
     * @throws LineBotException  if the board refused the request
     */
    public String request(String request) throws IOException {
        String reply = channel.exchange((c, timeout) -> {
            long sent = BrickChannel.LINK_TIME.nanoTime();
            c.send((request + "\n").getBytes(StandardCharsets.US_ASCII));
            String line = readLine(c, timeout);
            roundTrip.sample(BrickChannel.LINK_TIME.nanoTime() - sent);
            return line;
        });
        LineBotProtocol.Refusal refusal;
        try {
            refusal = LineBotProtocol.refusal(reply);
        } catch (IllegalArgumentException e) {
            throw lostFraming(e);
        }
        if (refusal != null) {
            throw new LineBotException(robot, request, refusal);
        }
        return reply;
    }

    /**
     * Sends a request whose reply must be {@code OK}.
     *
     * @param request the request
     * @throws IOException if the link failed, or the reply is not OK
     */
    public void command(String request) throws IOException {
        String reply = request(request);
        try {
            LineBotProtocol.ok(reply);
        } catch (IllegalArgumentException e) {
            throw lostFraming(e);
        }
    }

    /**
     * Checks the board's identity and protocol version.
     *
     * @throws IOException if it is not a LineBot speaking version {@value LineBotProtocol#VERSION}
     */
    public void hello() throws IOException {
        String reply = request(LineBotProtocol.hello());
        int version;
        try {
            version = LineBotProtocol.version(reply);
        } catch (IllegalArgumentException e) {
            throw new IOException("robot '" + robot + "': " + channel.describe() + " is not a LineBot: it answered HELLO with '" + reply + "'", e);
        }
        if (version != LineBotProtocol.VERSION) {
            throw new IOException("robot '" + robot + "': the LineBot on " + channel.describe() + " speaks protocol version " + version
                    + "; this driver speaks " + LineBotProtocol.VERSION);
        }
    }

    /**
     * @return A's and B's encoder counts, degrees
     * @throws IOException if the link failed
     */
    public int[] counts() throws IOException {
        String reply = request(LineBotProtocol.count());
        try {
            return LineBotProtocol.counts(reply);
        } catch (IllegalArgumentException e) {
            throw lostFraming(e);
        }
    }

    /**
     * @param input 1 or 2
     * @return its value
     * @throws IOException if the link failed
     */
    public int read(int input) throws IOException {
        String reply = request(LineBotProtocol.read(input));
        try {
            return LineBotProtocol.value(reply, input);
        } catch (IllegalArgumentException e) {
            throw lostFraming(e);
        }
    }

    private LinkLostException lostFraming(IllegalArgumentException e) {
        return new LinkLostException(channel.describe(), "robot '" + robot + "': " + e.getMessage() + "; the link lost its framing", e);
    }

    /** Reads bytes up to an LF, within one deadline for the whole line. */
    private String readLine(Communicator c, Duration timeout) throws IOException {
        Deadline deadline = Deadline.after(timeout);
        ByteArrayOutputStream line = new ByteArrayOutputStream(LineBotProtocol.MAX_LINE);
        while (true) {
            byte b = c.receiveExactly(1, deadline.remaining())[0];
            if (b == LineBotProtocol.LF) {
                return line.toString(StandardCharsets.US_ASCII);
            }
            if (line.size() == LineBotProtocol.MAX_LINE - 1) {
                throw new LinkLostException(channel.describe(), "robot '" + robot + "': a reply longer than " + LineBotProtocol.MAX_LINE
                        + " bytes without an LF; the link lost its framing");
            }
            line.write(b);
        }
    }
}
