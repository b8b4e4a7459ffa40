package io.robomw.platform.brick;

import io.robomw.api.spi.ConnectionSettings;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.Link;
import io.robomw.platform.link.LinkLostException;
import io.robomw.platform.link.SerialLink;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.link.TcpClientLink;
import io.robomw.platform.link.WireLog;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.locks.ReentrantLock;

/**
 * The request/reply channel to one brick, shared by its driver's motor and sensor platforms: one
 * exchange at a time (a brick answers in order), every reply awaited with a timeout, a lost link
 * reported by the exception of the exchange that found it. Whether the link is up is its owner's
 * to keep, the brick's {@link LinkAgent}: an exchange that fails tells it, an exchange while the
 * link is not up fails at once naming the robot, and the agent reopens the link (at most every
 * {@link #REOPEN_INTERVAL}), so a brick that comes back is used again without a restart. A channel
 * without an owner (a test's) just tries the link as it is.
 *
 * <p>Thread-safe: exchanges from the link thread and from program threads (sensor reads) are
 * serialised by a fair lock, which each waits for with a deadline (the reply timeout plus the time
 * the exchange under way is expected to take): a waiter never blocks for ever behind a stuck
 * exchange ({@link ChannelBusyException}).
 */
public final class BrickChannel implements AutoCloseable {

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
    /** The link agent that keeps the link's state, once one owns this channel. */
    private volatile Owner owner;
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

    /** What a channel tells, and asks, the one that keeps its link's state: its {@link LinkAgent}. */
    interface Owner {
        /**
         * @throws IOException (a {@link LinkLostException} naming the robot and the link) if the link
         *                     is not up: the exchange is not tried
         */
        void ensureUp() throws IOException;

        /**
         * An exchange failed: the link counts as lost.
         *
         * @param cause what it failed with
         */
        void lost(IOException cause);
    }

    /** @param o the link agent that keeps the link's state from now on */
    void ownedBy(Owner o) {
        owner = o;
    }

    /** @return the robot's name */
    public String robot() {
        return robot;
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
        Owner o = owner;
        if (o != null) {
            o.ensureUp();
        }
        acquire();
        try {
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
                if (o != null) {
                    o.lost(e);
                }
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

    /**
     * Closes and opens the link again, under the channel's lock (an exchange under way ends first,
     * or this waits as an exchange does); the owner calls it while the link is down.
     *
     * @throws IOException if the link cannot be opened, or the channel stays busy
     */
    public void reopen() throws IOException {
        acquire();
        try {
            communicator.reopen();
        } finally {
            lock.unlock();
        }
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
