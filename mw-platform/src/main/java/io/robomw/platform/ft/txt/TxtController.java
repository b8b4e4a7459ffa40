package io.robomw.platform.ft.txt;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkLostException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.Arrays;

/**
 * One fischertechnik TXT behind a {@link BrickChannel} (a TCP connection to port 65000), and the
 * online session on it. Each request is sent whole and its reply read by its fixed length, never
 * by timing; a reply with another id than the request's means the stream lost its framing and is
 * reported as a lost link, which the channel reopens.
 *
 * <h2>Session</h2>
 * Before the first request on a connection, and again on every connection the channel reopens,
 * the controller runs the handshake ftrobopy runs: queryStatus, startOnline, updateConfig with the
 * current configuration. Any failure ends the session, so the next request starts a new one on
 * the reopened connection; {@link Reading#session()} tells callers that counters may have
 * restarted. The configuration is every motor output a motor (as ftrobopy sets it) and each input
 * in the mode {@link #configureInput} last gave it, the rest as switches (ftrobopy's default).
 *
 * <p>Thread-safe: every request, the handshake and configuration changes run inside the channel's
 * exchange, which holds its lock.
 */
public final class TxtController {

    private static final Logger LOG = LoggerFactory.getLogger(TxtController.class);

    private final String robot;
    private final BrickChannel channel;
    // Guarded by the channel's lock (touched only inside channel.exchange):
    private final int[] inputMode = new int[TxtProtocol.INPUTS];
    private final int[] inputDigital = new int[TxtProtocol.INPUTS];
    private int configId;
    private int generation;
    private long sessions;
    private volatile boolean online;
    private volatile TxtProtocol.Status status;

    /**
     * @param robot   the robot's name, for messages
     * @param channel the channel to the TXT, open
     */
    public TxtController(String robot, BrickChannel channel) {
        this.robot = robot;
        this.channel = channel;
        Arrays.fill(inputMode, TxtProtocol.MODE_RESISTANCE);
        Arrays.fill(inputDigital, 1);
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
    }

    /** @return the link, for messages */
    public String describe() {
        return channel.describe();
    }

    /**
     * Starts the online session now (queryStatus, startOnline, updateConfig), so a TXT that is not
     * there is reported when the robot opens.
     *
     * @throws IOException if the TXT did not answer as it should
     */
    public void open() throws IOException {
        session((c, timeout) -> null);
    }

    /** @return what the TXT said about itself in the last handshake, or {@code null} before one */
    public TxtProtocol.Status status() {
        return status;
    }

    /** @return whether the session is up: the last request was answered */
    public boolean isOnline() {
        return online;
    }

    /**
     * Sets a universal input's mode and sends the configuration.
     *
     * @param input   0 for I1 ... 7 for I8
     * @param mode    {@link TxtProtocol#MODE_VOLTAGE}, {@link TxtProtocol#MODE_RESISTANCE} or {@link TxtProtocol#MODE_ULTRASONIC}
     * @param digital whether the TXT reports it as 0/1
     * @return the configuration's generation: readings of {@link #exchange} with this generation or
     *         later were taken in this mode
     * @throws IOException if the TXT did not acknowledge; the mode is kept and sent with the next handshake
     */
    public int configureInput(int input, int mode, boolean digital) throws IOException {
        return session((c, timeout) -> {
            inputMode[input] = mode;
            inputDigital[input] = digital ? 1 : 0;
            generation++;
            sendConfig(c, timeout);
            return generation;
        });
    }

    /**
     * One cyclic exchange: the outputs and commands go out, the inputs and counters come back.
     *
     * @param request the exchange
     * @return the reply, with the session and configuration generation it belongs to
     * @throws IOException if the link failed or lost its framing
     */
    public Reading exchange(TxtProtocol.Exchange request) throws IOException {
        byte[] message = request.encode();
        return session((c, timeout) -> {
            byte[] reply = request(c, timeout, message);
            return new Reading(TxtProtocol.ExchangeReply.decode(reply), sessions, generation);
        });
    }

    /**
     * Ends the online session with stopOnline, if it is up; a failure is only logged, since this
     * runs when the robot closes.
     */
    public void stopOnline() {
        if (!online) {
            return;
        }
        try {
            channel.exchange((c, timeout) -> {
                online = false;
                request(c, timeout, TxtProtocol.stopOnline());
                return null;
            });
        } catch (IOException e) {
            LOG.debug("robot '{}': stopOnline on {} failed: {}", robot, channel.describe(), e.getMessage());
        }
    }

    /**
     * A reply of the cyclic exchange.
     *
     * @param reply      the decoded reply
     * @param session    which handshake it belongs to (counts up from 1; a new one means the TXT
     *                   may have restarted its counters)
     * @param generation the configuration generation in force
     */
    public record Reading(TxtProtocol.ExchangeReply reply, long session, int generation) {
    }

    /** Runs a request inside the channel's exchange, after the handshake if the session is down. */
    private <T> T session(BrickChannel.Exchange<T> body) throws IOException {
        return channel.exchange((c, timeout) -> {
            try {
                if (!online) {
                    handshake(c, timeout);
                }
                return body.run(c, timeout);
            } catch (IOException | RuntimeException e) {
                online = false;
                throw e;
            }
        });
    }

    private void handshake(Communicator c, Duration timeout) throws IOException {
        TxtProtocol.Status s = TxtProtocol.Status.decode(request(c, timeout, TxtProtocol.queryStatus()));
        request(c, timeout, TxtProtocol.startOnline());
        sendConfig(c, timeout);
        sessions++;
        status = s;
        online = true;
        LOG.info("robot '{}': online with TXT '{}' (firmware {}) on {}", robot, s.deviceName(), s.versionText(), channel.describe());
    }

    private void sendConfig(Communicator c, Duration timeout) throws IOException {
        configId++;
        int[] motors = new int[TxtProtocol.MOTORS];
        Arrays.fill(motors, 1);
        int[] counters = new int[TxtProtocol.COUNTERS];
        Arrays.fill(counters, 1);
        TxtProtocol.Config config = new TxtProtocol.Config(configId, 0, motors, inputMode, inputDigital, counters,
                new int[TxtProtocol.CONFIG_MOTOR_CONFIG_COUNT]);
        request(c, timeout, config.encode());
    }

    /** Sends a request and reads its reply by the table's length, checking the reply's id. */
    private byte[] request(Communicator c, Duration timeout, byte[] message) throws IOException {
        long id = TxtProtocol.messageId(message);
        c.send(message);
        byte[] reply = c.receiveExactly(TxtProtocol.replyLength(id), timeout);
        long got = TxtProtocol.messageId(reply);
        if (got != TxtProtocol.replyId(id)) {
            throw new LinkLostException(channel.describe(), String.format("expected the reply to %s (id 0x%08X), got id 0x%08X; the link lost its framing",
                    TxtProtocol.name(id), TxtProtocol.replyId(id), got));
        }
        return reply;
    }
}
