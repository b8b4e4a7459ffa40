package io.robomw.platform.aibo;

import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.LinkTimeoutException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Consumer;

/**
 * One URBI session with a robot over a {@link Communicator}: commands go out through a queue, every
 * message that comes back is handed to the handler registered for its tag.
 *
 * <h2>Threads</h2>
 * <ul>
 *   <li>The <b>writer</b> ({@code <robot>-urbi-writer}) sends what {@link #send} queued, in order, so
 *   no caller (the execution action thread above all) ever waits for the network. A full queue
 *   ({@value #OUTBOX} commands) refuses the command.</li>
 *   <li>The <b>reader</b> ({@code <robot>-urbi-reader}) decodes what arrives and calls the handler
 *   of each message's tag, then reopens a lost link (at most every {@link #REOPEN_INTERVAL}): on a
 *   new connection it drops what was still queued for the old one, sends the startup command and
 *   every stream again, and tells the {@link Events}.</li>
 * </ul>
 * Both catch anything thrown: a failing handler is logged and counted and the session goes on; a
 * failure of the thread itself is logged, reported as a lost link and ends the thread, so nothing
 * dies silently. Handlers run on the reader and must be quick.
 */
final class UrbiConnection implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(UrbiConnection.class);
    /** The link's time (reopen pacing): the wall clock, as {@code BrickChannel}'s, from the Clock rather than System.nanoTime. */
    private static final io.robomw.api.Clock LINK_TIME = io.robomw.api.Clock.system();
    /** One line a second at most about malformed lines: a flood of garbage must not flood the log. */
    private final io.robomw.platform.ThrottledWarnings malformedWarnings = new io.robomw.platform.ThrottledWarnings(LOG, java.time.Duration.ofSeconds(1), LINK_TIME);

    /** Commands that may wait in the queue. */
    static final int OUTBOX = 1024;
    /** Shortest time between two attempts to reopen a lost link. */
    static final Duration REOPEN_INTERVAL = Duration.ofMillis(500);
    private static final Duration POLL = Duration.ofMillis(100);

    /** What the session tells its owner. */
    interface Events {
        /**
         * @param cause why the link was lost
         */
        void lost(IOException cause);

        /** The link works again: the startup command and the streams were sent anew. */
        void restored();
    }

    private final String robot;
    private final Communicator communicator;
    private final Duration replyTimeout;
    private final String startup;
    private final BlockingQueue<byte[]> outbox = new ArrayBlockingQueue<>(OUTBOX);
    private final Map<String, Consumer<UrbiReply>> handlers = new ConcurrentHashMap<>();
    private final List<byte[]> streams = new CopyOnWriteArrayList<>();
    private final AtomicLong tags = new AtomicLong();
    private final AtomicBoolean down = new AtomicBoolean();
    private final AtomicLong handlerErrors = new AtomicLong();
    private final AtomicLong malformed = new AtomicLong();
    private final UrbiReplyDecoder decoder = new UrbiReplyDecoder();
    private volatile Events events = new Events() {
        @Override
        public void lost(IOException cause) {
        }

        @Override
        public void restored() {
        }
    };
    private volatile boolean running;
    private volatile boolean closing;
    private volatile String lastUntaggedError = "";
    private Thread reader;
    private Thread writer;
    private long lastReopen;
    /** Guards the counts below and the waiters: what was queued, and how much of it the writer has settled. */
    private final Object progress = new Object();
    /** Commands queued so far. */
    private long queued;
    /** Commands the writer has written (or, once the link was lost, dropped) so far: always a prefix of those queued. */
    private long settled;
    /** Callers waiting for the commands queued before them to be written, each with that count. */
    private final List<Written> waiters = new java.util.ArrayList<>();

    /** A caller of {@link #written()}, waiting until {@code upTo} commands have been written. */
    private record Written(long upTo, CompletableFuture<Void> future) {
    }

    /**
     * @param robot        the robot's name, for thread names and messages
     * @param communicator the link, not yet open
     * @param replyTimeout how long a reply may take
     * @param startup      the command sent when a connection opens (the motors on, settings)
     */
    UrbiConnection(String robot, Communicator communicator, Duration replyTimeout, String startup) {
        this.robot = robot;
        this.communicator = communicator;
        this.replyTimeout = replyTimeout;
        this.startup = startup;
    }

    /** @param events told when the link is lost and restored */
    void events(Events events) {
        this.events = events;
    }

    /** @return the link, for messages */
    String describe() {
        return communicator.describe();
    }

    /** @return how long a reply may take */
    Duration replyTimeout() {
        return replyTimeout;
    }

    /**
     * Connects, starts the threads, sends the startup command and waits for its end.
     *
     * @throws IOException if the robot cannot be reached, or does not answer the startup command
     *                     within the reply timeout, or answers it with an error
     */
    void open() throws IOException {
        communicator.open();
        running = true;
        reader = new Thread(this::readLoop, robot + "-urbi-reader");
        reader.setDaemon(true);
        writer = new Thread(this::writeLoop, robot + "-urbi-writer");
        writer.setDaemon(true);
        reader.start();
        writer.start();
        CompletableFuture<Void> done = sendStartup();
        try {
            done.get(replyTimeout.toMillis(), TimeUnit.MILLISECONDS);
        } catch (TimeoutException e) {
            close();
            throw new IOException("robot '" + robot + "': " + describe() + " did not end the startup command '" + startup + "' within "
                    + replyTimeout.toMillis() + " ms (no '*** end'); is it an URBI server?"
                    + (lastUntaggedError.isEmpty() ? "" : " It said: !!! " + lastUntaggedError), e);
        } catch (ExecutionException e) {
            close();
            throw new IOException("robot '" + robot + "': " + describe() + " refused the startup command '" + startup + "': " + e.getCause().getMessage(),
                    e.getCause());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            close();
            throw new IOException("robot '" + robot + "': interrupted while opening " + describe(), e);
        }
    }

    private CompletableFuture<Void> sendStartup() {
        CompletableFuture<Void> done = new CompletableFuture<>();
        String tag = newTag("o");
        handlers.put(tag, r -> {
            if (r.kind() == UrbiReply.Kind.ERROR) {
                handlers.remove(tag);
                done.completeExceptionally(new IOException("!!! " + r.text()));
            } else if (r.isEnd()) {
                handlers.remove(tag);
                done.complete(null);
            }
        });
        if (!send(UrbiProtocol.command(tag, startup))) {
            done.completeExceptionally(new IOException("the link is down"));
        }
        return done;
    }

    /**
     * @param prefix a letter, for the kind of command ({@code c} command, {@code r} read, {@code s} stream)
     * @return a tag no other command of this session has
     */
    String newTag(String prefix) {
        return prefix + tags.incrementAndGet();
    }

    /**
     * @param tag     a tag
     * @param handler called on the reader with each message of that tag
     */
    void register(String tag, Consumer<UrbiReply> handler) {
        handlers.put(tag, handler);
    }

    /** @param tag a tag whose messages are no longer wanted */
    void forget(String tag) {
        handlers.remove(tag);
    }

    /**
     * Queues bytes for the link. Never blocks.
     *
     * @param bytes an encoded command
     * @return false if the link is down or the queue is full (the command was not queued)
     */
    boolean send(byte[] bytes) {
        if (down.get() || !running || closing) {
            return false;
        }
        boolean offered;
        synchronized (progress) {
            offered = outbox.offer(bytes);
            if (offered) {
                queued++;
            }
        }
        if (!offered) {
            LOG.warn("robot '{}': {} commands are waiting for {}; refused one", robot, OUTBOX, describe());
        }
        return offered;
    }

    /**
     * @return completes once the writer has written every command queued before this call to the
     *         link (at once if none waits); fails with an {@link IOException} if the link is down or
     *         is lost first, or the session closes
     */
    CompletableFuture<Void> written() {
        synchronized (progress) {
            if (down.get() || !running) {
                return CompletableFuture.failedFuture(new IOException(describe() + " is down"));
            }
            if (settled >= queued) {
                return CompletableFuture.completedFuture(null);
            }
            CompletableFuture<Void> f = new CompletableFuture<>();
            waiters.add(new Written(queued, f));
            return f;
        }
    }

    /** One more queued command was written (or dropped: {@code written} false); completes the waiters it settles. */
    private void settled(boolean written) {
        List<CompletableFuture<Void>> done = null;
        synchronized (progress) {
            if (settled < queued) {
                settled++; // not past what was queued: a reopen may have settled the command this one was, already
            }
            if (written && !waiters.isEmpty()) {
                for (java.util.Iterator<Written> i = waiters.iterator(); i.hasNext(); ) {
                    Written w = i.next();
                    if (w.upTo() <= settled) {
                        i.remove();
                        if (done == null) {
                            done = new java.util.ArrayList<>(2);
                        }
                        done.add(w.future());
                    }
                }
            }
        }
        if (done != null) {
            done.forEach(f -> f.complete(null));
        }
    }

    /** Fails every waiter: what they wait for will not be written. */
    private void failWaiters(IOException why) {
        List<Written> failed;
        synchronized (progress) {
            failed = List.copyOf(waiters);
            waiters.clear();
        }
        failed.forEach(w -> w.future().completeExceptionally(why));
    }

    /**
     * Streams a device's value from now on, and again on every new connection.
     *
     * @param bytes the encoded stream command ({@link UrbiProtocol#stream})
     * @return whether it was queued now
     */
    boolean addStream(byte[] bytes) {
        streams.add(bytes);
        return send(bytes);
    }

    /** @return whether the link is down */
    boolean isDown() {
        return down.get();
    }

    /** @return the last error the server sent without a tag (a line it could not parse), or "" */
    String lastUntaggedError() {
        return lastUntaggedError;
    }

    /** @return exceptions thrown by handlers */
    long handlerErrors() {
        return handlerErrors.get();
    }

    /** @return lines from the server that were not messages */
    long malformedLines() {
        return malformed.get();
    }

    // ---- writer ----

    private void writeLoop() {
        try {
            while (running) {
                byte[] next = outbox.poll(POLL.toMillis(), TimeUnit.MILLISECONDS);
                if (next == null) {
                    if (closing) {
                        return;
                    }
                    continue;
                }
                if (down.get()) {
                    settled(false);
                    continue;
                }
                try {
                    communicator.send(next);
                    settled(true);
                } catch (IOException e) {
                    settled(false);
                    if (running) {
                        markDown(e);
                    }
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } catch (Throwable t) {
            LOG.error("robot '{}': the URBI writer failed; the link counts as lost", robot, t);
            markDown(new IOException("the URBI writer failed: " + t, t));
        }
    }

    // ---- reader ----

    private void readLoop() {
        UrbiReplyDecoder.Listener listener = new UrbiReplyDecoder.Listener() {
            @Override
            public void reply(UrbiReply reply) {
                dispatch(reply);
            }

            @Override
            public void malformed(String why, String excerpt) {
                long n = malformed.incrementAndGet();
                malformedWarnings.warn("robot '{}': {} sent a line that is not an URBI message ({} so far): {}: \"{}\"", robot, describe(), n, why, excerpt);
            }
        };
        try {
            while (running) {
                if (down.get()) {
                    reopen();
                    continue;
                }
                byte[] chunk;
                try {
                    chunk = communicator.receive(POLL);
                } catch (LinkTimeoutException e) {
                    continue;
                } catch (IOException e) {
                    if (running) {
                        markDown(e);
                    }
                    continue;
                }
                decoder.feed(chunk, 0, chunk.length, listener);
            }
        } catch (Throwable t) {
            LOG.error("robot '{}': the URBI reader failed; the link counts as lost and is not reopened", robot, t);
            markDown(new IOException("the URBI reader failed: " + t, t));
        }
    }

    private void dispatch(UrbiReply reply) {
        Consumer<UrbiReply> h = reply.tagged() ? handlers.get(reply.tag()) : null;
        if (h == null) {
            if (reply.kind() == UrbiReply.Kind.ERROR) {
                lastUntaggedError = reply.text();
                LOG.warn("robot '{}': {} reported an error{}: {}", robot, describe(), reply.tagged() ? " for tag " + reply.tag() : "", reply.describe());
            } else {
                LOG.debug("robot '{}': {}", robot, reply.describe());
            }
            return;
        }
        try {
            h.accept(reply);
        } catch (RuntimeException e) {
            long n = handlerErrors.incrementAndGet();
            LOG.error("robot '{}': handling {} failed ({} so far)", robot, reply.describe(), n, e);
        }
    }

    private void markDown(IOException cause) {
        if (down.compareAndSet(false, true)) {
            lastReopen = 0;
            failWaiters(cause);
            LOG.warn("robot '{}': lost {}: {}", robot, describe(), cause.getMessage());
            try {
                events.lost(cause);
            } catch (RuntimeException e) {
                LOG.error("robot '{}': reporting the lost link failed", robot, e);
            }
        }
    }

    private void reopen() {
        long now = LINK_TIME.nanoTime();
        if (lastReopen != 0 && now - lastReopen < REOPEN_INTERVAL.toNanos()) {
            java.util.concurrent.locks.LockSupport.parkNanos(this, REOPEN_INTERVAL.toNanos() - (now - lastReopen));
            return;
        }
        lastReopen = LINK_TIME.nanoTime();
        try {
            communicator.reopen();
        } catch (IOException e) {
            LOG.debug("robot '{}': reopening {} failed: {}", robot, describe(), e.getMessage());
            return;
        }
        synchronized (progress) {
            outbox.clear(); // dropped, with the old connection
            settled = queued;
        }
        decoder.reset();
        down.set(false);
        LOG.info("robot '{}': reconnected {}", robot, describe());
        sendStartup().whenComplete((v, e) -> {
            if (e != null) {
                LOG.error("robot '{}': {} refused the startup command '{}' on the new connection: {}", robot, describe(), startup, e.getMessage());
            }
        });
        for (byte[] s : streams) {
            send(s);
        }
        try {
            events.restored();
        } catch (RuntimeException e) {
            LOG.error("robot '{}': reporting the restored link failed", robot, e);
        }
    }

    /**
     * Lets the writer send what is still queued (the stops of the last commands; waiting at most
     * the reply timeout), then stops both threads and closes the link. Idempotent.
     */
    @Override
    public void close() {
        closing = true;
        join(writer, replyTimeout.toMillis() + POLL.toMillis());
        running = false;
        communicator.close();
        join(writer, 2000);
        join(reader, 2000);
        failWaiters(new IOException(describe() + " was closed"));
    }

    private static void join(Thread t, long millis) {
        if (t == null || t == Thread.currentThread()) {
            return;
        }
        try {
            t.join(millis);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

}
