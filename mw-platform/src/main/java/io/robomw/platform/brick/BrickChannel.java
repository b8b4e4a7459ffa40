package io.robomw.platform.brick;

import io.robomw.api.spi.ConnectionSettings;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.SerialLink;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.link.TcpClientLink;
import io.robomw.platform.link.WireLog;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.locks.ReentrantLock;

/**
 * The request/reply channel to one brick, shared by its driver's motor and sensor platforms: one
 * exchange at a time (a brick answers in order), every reply awaited with a timeout, a lost link
 * reported by the exception of the exchange that found it, and reopened by a later exchange (at
 * most every {@link #REOPEN_INTERVAL}), so a brick that comes back is used again without a
 * restart.
 *
 * <p>Thread-safe: exchanges from the link thread and from program threads (sensor reads) are
 * serialised by a fair lock, which each waits for with a deadline (the reply timeout plus the time
 * the exchange under way is expected to take): a waiter never blocks for ever behind a stuck
 * exchange ({@link ChannelBusyException}).
 */
public final class BrickChannel implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(BrickChannel.class);

    /** Shortest time between two attempts to reopen a lost link. */
    public static final Duration REOPEN_INTERVAL = Duration.ofMillis(500);

    /**
     * The link's time: exchanges are timed and a lost link's reopening paced on the wall clock (a
     * link's real time, whatever clock the robot runs on), always read through this {@link io.robomw.api.Clock}.
     */
    public static final io.robomw.api.Clock LINK_TIME = io.robomw.api.Clock.system();

    private final String robot;
    private final Communicator communicator;
    private final Duration replyTimeout;
    private final ReentrantLock lock = new ReentrantLock(true);
    private boolean down;
    private long lastAttempt;
    /**
     * The least time the first exchange on a newly opened channel waits for its replies: a brick
     * just connected (a Bluetooth link still being set up, an emulator whose process has only just
     * started on a loaded host) can take longer to answer its first telegram than any later one.
     */
    public static final Duration FIRST_REPLY_TIMEOUT = Duration.ofSeconds(2);

    private static Duration max(Duration a, Duration b) {
        return a.compareTo(b) >= 0 ? a : b;
    }

    /** Whether an exchange has succeeded on this channel; guarded by the lock. */
    private boolean answered;
    private volatile long exchangeStartedAt;
    private volatile boolean exchanging;
    private final RoundTripEstimate exchangeTime = new RoundTripEstimate();

    /**
     * @param robot        the robot's name, for messages
     * @param communicator the opened communicator
     * @param replyTimeout how long to wait for each reply
     */
    public BrickChannel(String robot, Communicator communicator, Duration replyTimeout) {
        this.robot = robot;
        this.communicator = communicator;
        this.replyTimeout = replyTimeout;
    }

    /**
     * Opens the link a robot description's {@code connection:} block names: {@code port} (a
     * serial device path) with {@code baud}, or {@code host} and {@code port} for TCP; an optional
     * {@code wire_log} file records every byte.
     *
     * @param robot      the robot's name
     * @param connection the connection block
     * @param defaults   serial settings when the block gives none
     * @param tcpPort    the TCP port when the block gives a host but no port
     * @param replyTimeout how long to wait for replies
     * @return the open channel
     * @throws IOException if the link cannot be opened; the message names it
     */
    public static BrickChannel open(String robot, ConnectionSettings connection, SerialSettings defaults, int tcpPort,
                                    Duration replyTimeout) throws IOException {
        Link link;
        if (connection.text("host").isPresent()) {
            link = new TcpClientLink(connection.requireText("host"), connection.integer("port", tcpPort), Duration.ofSeconds(5));
        } else {
            SerialSettings s = SerialSettings.of(connection.integer("baud", defaults.baud()), defaults.dataBits(), defaults.parity(), defaults.stopBits());
            link = new SerialLink(connection.requireText("port"), s);
        }
        WireLog log = connection.text("wire_log").isPresent() ? WireLog.open(Path.of(connection.requireText("wire_log"))) : null;
        Communicator c = log == null ? new Communicator(link) : new Communicator(link, log);
        try {
            c.open();
        } catch (IOException e) {
            c.close();
            throw e;
        }
        return new BrickChannel(robot, c, replyTimeout);
    }

    /** @return the link, for messages */
    public String describe() {
        return communicator.describe();
    }

    /** @return the communicator, for drivers that read replies themselves inside {@link #exchange} */
    public Communicator communicator() {
        return communicator;
    }

    /**
     * How long until the exchange under way is expected to end (by the smoothed time exchanges
     * take): a command handed to the channel now waits that long before it is sent.
     *
     * @return nanoseconds, 0 if no exchange is under way
     */
    public long nanosUntilFree() {
        if (!exchanging) {
            return 0;
        }
        return Math.max(0, exchangeStartedAt + exchangeTime.nanos() - LINK_TIME.nanoTime());
    }

    /** @return how long each reply is awaited */
    public Duration replyTimeout() {
        return replyTimeout;
    }

    /**
     * Runs one exchange (send, then read the reply) with the channel to itself.
     *
     * @param exchange what to send and how to read the reply
     * @param <T>      the decoded reply
     * @return the decoded reply
     * @throws IOException if the link is down (and could not be reopened yet) or failed during the exchange
     */
    public <T> T exchange(Exchange<T> exchange) throws IOException {
        acquire();
        try {
            ensureOpen();
            long started = LINK_TIME.nanoTime();
            exchangeStartedAt = started;
            exchanging = true;
            try {
                Duration timeout = replyTimeoutNow();
                T result = exchange.run(communicator, timeout);
                answered = true;
                exchangeTime.sample(LINK_TIME.nanoTime() - started);
                return result;
            } catch (IOException e) {
                markDown(e);
                throw e;
            } finally {
                exchanging = false;
            }
        } finally {
            lock.unlock();
        }
    }

    /** How long a reply is awaited now: longer on a channel that has not answered yet. */
    private Duration replyTimeoutNow() {
        return answered ? replyTimeout : max(replyTimeout, FIRST_REPLY_TIMEOUT);
    }

    /**
     * Takes the channel, waiting at most the reply timeout plus the time the exchange under way is
     * expected to take still (at least another reply timeout): an exchange under way ends by its
     * own timeouts, so a waiter is never held longer than it could take.
     *
     * @throws ChannelBusyException naming the robot and the link, if the wait runs out
     * @throws java.io.InterruptedIOException if the waiting thread is interrupted
     */
    private void acquire() throws IOException {
        long timeout = replyTimeoutNow().toNanos();
        long wait = timeout + Math.max(timeout, nanosUntilFree());
        boolean locked;
        try {
            locked = lock.tryLock(wait, java.util.concurrent.TimeUnit.NANOSECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            java.io.InterruptedIOException i = new java.io.InterruptedIOException("robot '" + robot + "': interrupted while waiting for "
                    + communicator.describe());
            i.initCause(e);
            throw i;
        }
        if (!locked) {
            throw new ChannelBusyException(robot, communicator.describe(), Duration.ofNanos(wait));
        }
    }

    private void ensureOpen() throws IOException {
        if (!down) {
            return;
        }
        long now = LINK_TIME.nanoTime();
        if (now - lastAttempt < REOPEN_INTERVAL.toNanos()) {
            throw new LinkLostException(communicator.describe(), "link to robot '" + robot + "' is down; next reopen attempt within "
                    + REOPEN_INTERVAL.toMillis() + " ms");
        }
        lastAttempt = now;
        communicator.reopen();
        down = false;
        LOG.info("robot '{}': reopened {}", robot, communicator.describe());
    }

    private void markDown(IOException e) {
        if (!down) {
            LOG.warn("robot '{}': link {} failed: {}", robot, communicator.describe(), e.getMessage());
        }
        down = true;
        lastAttempt = LINK_TIME.nanoTime();
    }

    /** Closes the link. */
    @Override
    public void close() {
        communicator.close();
    }

    /**
     * One request and its reply.
     *
     * @param <T> the decoded reply
     */
    @FunctionalInterface
    public interface Exchange<T> {
        /**
         * @param communicator the link
         * @param timeout      how long to wait for the reply
         * @return the decoded reply
         * @throws IOException if the link failed or the reply did not come in time
         */
        T run(Communicator communicator, Duration timeout) throws IOException;
    }
}
