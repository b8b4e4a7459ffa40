package io.robomw.console.foxglove;

import org.eclipse.jetty.websocket.api.Callback;
import org.eclipse.jetty.websocket.api.Session;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.ByteBuffer;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * One connected Foxglove client: its subscriptions (by its own ids), the channels it advertised
 * to publish on, and what waits to be sent to it ({@link OutQueue}: one frame on its way at a time,
 * control before data, the oldest data dropped when the client is slow). A bad message from the
 * client is answered with a status error and the connection goes on.
 *
 * <p>Threads: Jetty calls the {@code onWebSocket...} methods one at a time; the server's encoder
 * and drive threads queue frames concurrently. The queue and the count of frames in flight are guarded by
 * {@code this}; subscriptions and client channels are touched only by Jetty's calls. Public only
 * because Jetty calls its listener methods through method handles.
 */
public final class ClientSession extends Session.Listener.AbstractAutoDemanding {

    private static final Logger LOG = LoggerFactory.getLogger(ClientSession.class);
    /** The longest a status error about a drive failure is repeated for the same robot and text. */
    private static final long DRIVE_ERROR_REPEAT_NANOS = 2_000_000_000L;
    /**
     * Frames handed to Jetty and not yet written, at most: enough for Jetty to write many frames
     * in one go, few enough that a slow client's backlog stays in {@link OutQueue}, where the
     * oldest data is dropped.
     */
    static final int MAX_IN_FLIGHT = 64;

    private final FoxgloveServer server;
    private final Subprotocol subprotocol;
    private final boolean mayPublish;
    private final String peer;
    private final OutQueue queue;
    /** The client's subscription id to the channel it is on. */
    private final Map<Long, ChannelState> subscriptions = new HashMap<>();
    /** The client's channel id to what it advertised, and the robot its Twists drive (null: ignored). */
    private final Map<Long, Publication> publications = new HashMap<>();
    private final Map<String, String> lastDriveError = new HashMap<>();
    private final Map<String, Long> lastDriveErrorAt = new HashMap<>();
    private final AtomicInteger pumping = new AtomicInteger();
    private int inFlight;
    private boolean gone;

    /** A channel the client publishes on. @param robot the robot its Twists drive, or null if they are ignored */
    record Publication(ClientRequest.ClientChannel channel, String robot) {
    }

    ClientSession(FoxgloveServer server, Subprotocol subprotocol, boolean mayPublish, String peer, int backlog) {
        this.server = server;
        this.subprotocol = subprotocol;
        this.mayPublish = mayPublish;
        this.peer = peer;
        this.queue = new OutQueue(backlog, backlog);
    }

    /** @return the subprotocol the handshake chose */
    Subprotocol subprotocol() {
        return subprotocol;
    }

    /** @return whether this client may publish (drive robots) */
    boolean mayPublish() {
        return mayPublish;
    }

    /** @return the client's address, for logs and errors */
    String peer() {
        return peer;
    }

    @Override
    public void onWebSocketOpen(Session session) {
        super.onWebSocketOpen(session);
        server.opened(this);
    }

    // ---- what the client sends ----

    @Override
    public void onWebSocketText(String text) {
        ClientRequest r;
        try {
            r = ClientRequest.parse(text);
        } catch (ClientRequest.BadRequest e) {
            refuse(e.getMessage());
            return;
        }
        if (r instanceof ClientRequest.Subscribe s) {
            for (ClientRequest.Subscription sub : s.subscriptions()) {
                subscribe(sub);
            }
        } else if (r instanceof ClientRequest.Unsubscribe u) {
            for (long id : u.subscriptionIds()) {
                ChannelState c = subscriptions.remove(id);
                if (c != null) {
                    c.unsubscribe(this, id);
                } // as the SDK: an unknown subscription id is ignored
            }
        } else if (r instanceof ClientRequest.Advertise a) {
            advertise(a);
        } else if (r instanceof ClientRequest.Unadvertise u) {
            for (long id : u.channelIds()) {
                Publication p = publications.remove(id);
                if (p == null) {
                    status(StatusLevel.WARNING, "Client is not advertising channel: " + id + "; ignoring unadvertisement");
                } else if (p.robot() != null) {
                    server.driver().release(p.robot(), this);
                }
            }
        } else if (r instanceof ClientRequest.Unsupported u) {
            refuse(u.answer());
        }
    }

    private void subscribe(ClientRequest.Subscription sub) {
        ChannelState c = server.channel(sub.channelId());
        if (c == null) {
            refuse("Unknown channel ID: " + sub.channelId());
            return;
        }
        if (subscriptions.containsKey(sub.id())) {
            refuse("Subscription ID was already used: " + sub.id() + "; ignoring subscription");
            return;
        }
        if (subscriptions.containsValue(c)) {
            status(StatusLevel.WARNING, "Client is already subscribed to channel: " + sub.channelId() + "; ignoring subscription");
            return;
        }
        if (subscriptions.size() >= FoxgloveServer.MAX_SUBSCRIPTIONS) {
            refuse("Too many subscriptions: a client may hold " + FoxgloveServer.MAX_SUBSCRIPTIONS + "; ignoring subscription to channel " + sub.channelId());
            return;
        }
        subscriptions.put(sub.id(), c);
        c.subscribe(this, sub.id());
    }

    private void advertise(ClientRequest.Advertise a) {
        if (!server.offersClientPublish() || !mayPublish) {
            refuse("Server does not support clientPublish capability"
                    + (server.offersClientPublish() ? " for a page from this origin: only programs, Foxglove's web app and pages of this machine may drive robots" : ""));
            return;
        }
        for (ClientRequest.ClientChannel ch : a.channels()) {
            if (publications.containsKey(ch.id())) {
                status(StatusLevel.WARNING, "Client is already advertising channel: " + ch.id() + "; ignoring advertisement");
                continue;
            }
            if (publications.size() >= FoxgloveServer.MAX_CLIENT_CHANNELS) {
                refuse("Too many client channels: a client may advertise " + FoxgloveServer.MAX_CLIENT_CHANNELS + "; ignoring channel " + ch.id());
                continue;
            }
            String robot = server.robotFor(ch.topic()).orElse(null);
            String why = null;
            if (robot == null) {
                why = "RoboMW drives a robot R from Twists on /robots/R/cmd_vel" + server.describeDrivable() + "; messages on " + ch.topic() + " are ignored";
            } else if (!ch.encoding().equals("json")) {
                why = "RoboMW takes Twists as JSON (encoding \"json\"), not \"" + ch.encoding() + "\"; messages on " + ch.topic() + " are ignored";
                robot = null;
            } else if (!Twist.SCHEMA_NAMES.contains(ch.schemaName())) {
                why = "RoboMW takes " + Twist.SCHEMA_NAMES.stream().sorted().toList() + " on " + ch.topic() + ", not \"" + ch.schemaName()
                        + "\"; messages on it are ignored";
                robot = null;
            }
            publications.put(ch.id(), new Publication(ch, robot));
            if (why != null) {
                status(StatusLevel.WARNING, why);
            } else {
                LOG.info("foxglove: client {} drives robot {} through {}", peer, robot, ch.topic());
            }
        }
    }

    @Override
    public void onWebSocketBinary(ByteBuffer payload, org.eclipse.jetty.websocket.api.Callback callback) {
        try {
            BinaryFrames.ClientMessage m = BinaryFrames.parseClient(payload);
            Publication p = publications.get(m.channelId());
            if (p == null) {
                refuse("Unknown channel ID: " + m.channelId());
            } else if (p.robot() != null) {
                try {
                    server.driver().submit(p.robot(), Twist.parse(m.payload()), this);
                } catch (IOException e) {
                    refuse("message on channel " + m.channelId() + " (" + p.channel().topic() + "): " + e.getMessage());
                }
            }
        } catch (ClientRequest.BadRequest e) {
            refuse(e.getMessage());
        } finally {
            callback.succeed();
        }
    }

    /** Tells the client its robot could not drive (the same error at most every two seconds). */
    void driveFailed(String robot, String message) {
        long now = System.nanoTime();
        synchronized (lastDriveError) {
            Long at = lastDriveErrorAt.get(robot);
            if (message.equals(lastDriveError.get(robot)) && at != null && now - at < DRIVE_ERROR_REPEAT_NANOS) {
                return;
            }
            lastDriveError.put(robot, message);
            lastDriveErrorAt.put(robot, now);
        }
        status(StatusLevel.ERROR, "robot " + robot + " could not drive: " + message);
    }

    private void refuse(String message) {
        LOG.debug("foxglove: refused a message from {}: {}", peer, message);
        status(StatusLevel.ERROR, message);
    }

    void status(StatusLevel level, String message) {
        sendControl(ServerMessages.status(level, message));
    }

    // ---- what goes to the client ----

    /** Queues a control message; a client whose control queue is full is disconnected. */
    void sendControl(String json) {
        boolean full;
        synchronized (this) {
            if (gone) {
                return;
            }
            full = !queue.offerControl(OutQueue.Frame.text(json));
        }
        if (full) {
            LOG.warn("foxglove: client {} does not keep up with the server's control messages; disconnecting it", peer);
            close(1008, "too slow: the control queue is full");
            return;
        }
        pump();
    }

    /** Queues a data frame; a full data queue drops its oldest. */
    void sendData(ByteBuffer frame) {
        synchronized (this) {
            if (gone) {
                return;
            }
            long before = queue.dropped();
            queue.offerData(OutQueue.Frame.binary(frame));
            if (before == 0 && queue.dropped() > 0) {
                LOG.info("foxglove: client {} is slower than the data: its oldest queued messages are being dropped", peer);
            }
        }
        pump();
    }

    /** @return data frames dropped for this client so far */
    synchronized long dropped() {
        return queue.dropped();
    }

    /**
     * Hands what is queued to Jetty, up to {@value #MAX_IN_FLIGHT} frames not yet written. A send
     * that completes at once calls back into here; the counter turns that into one more round of
     * the outer loop instead of a deeper stack.
     */
    private void pump() {
        if (pumping.getAndIncrement() != 0) {
            return;
        }
        do {
            while (true) {
                OutQueue.Frame f;
                Session s = getSession();
                synchronized (this) {
                    f = inFlight >= MAX_IN_FLIGHT || gone || s == null ? null : queue.poll();
                    if (f != null) {
                        inFlight++;
                    }
                }
                if (f == null) {
                    break;
                }
                Callback done = Callback.from(this::sent, this::failed);
                if (f.text() != null) {
                    s.sendText(f.text(), done);
                } else {
                    s.sendBinary(f.binary(), done);
                }
            }
        } while (pumping.decrementAndGet() != 0);
    }

    private void sent() {
        synchronized (this) {
            inFlight--;
        }
        pump();
    }

    private void failed(Throwable failure) {
        LOG.debug("foxglove: sending to {} failed: {}", peer, failure.toString());
        synchronized (this) {
            inFlight--;
            gone = true;
            queue.clear();
        }
    }

    // ---- the end ----

    @Override
    public void onWebSocketClose(int status, String reason) {
        ended();
    }

    @Override
    public void onWebSocketError(Throwable cause) {
        LOG.debug("foxglove: connection with {} failed: {}", peer, cause.toString());
        ended();
    }

    private void ended() {
        List<Map.Entry<Long, ChannelState>> subs;
        List<Publication> pubs;
        synchronized (this) {
            gone = true;
            queue.clear();
        }
        subs = new ArrayList<>(subscriptions.entrySet());
        pubs = new ArrayList<>(publications.values());
        subscriptions.clear();
        publications.clear();
        for (Map.Entry<Long, ChannelState> e : subs) {
            e.getValue().unsubscribe(this, e.getKey());
        }
        for (Publication p : pubs) {
            if (p.robot() != null) {
                server.driver().release(p.robot(), this);
            }
        }
        server.closed(this);
    }

    /** Closes the connection (the server is stopping, or the client is too slow). */
    void close(int status, String reason) {
        Session s = getSession();
        if (s != null && s.isOpen()) {
            s.close(status, reason, Callback.NOOP);
        }
    }

    /** Sends a ping, so a connection that is only watched stays open and a dead one is noticed. */
    void ping() {
        Session s = getSession();
        if (s != null && s.isOpen()) {
            s.sendPing(ByteBuffer.allocate(0), Callback.NOOP);
        }
    }

    @Override
    public String toString() {
        return "foxglove client " + peer;
    }
}
