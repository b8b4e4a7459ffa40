package io.robomw.agents.messaging.rmi;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.io.OutboundBuffer;
import io.robomw.agents.messaging.spi.Endpoint;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.rmi.NoSuchObjectException;
import java.rmi.RemoteException;
import java.rmi.registry.Registry;
import java.rmi.server.RemoteServer;
import java.rmi.server.ServerNotActiveException;
import java.rmi.server.UnicastRemoteObject;
import java.security.SecureRandom;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;

/**
 * The server side of the RMI transport: the exported {@link FrameEndpoint} and its sessions.
 * Frames a client delivers are handed to the node on RMI's call thread (listeners run there).
 * A session that has not polled for {@value #SESSION_TIMEOUT_SECONDS} s is closed; at most
 * {@link io.robomw.agents.messaging.PeerLimits#maxConnections()} sessions are open at once (one more
 * is refused with a {@link RemoteException} naming the limit), and a call's byte array may not be
 * larger than one outbound buffer (RMI's deserialization filter refuses it before it is read).
 */
final class RmiEndpoint implements Endpoint, FrameEndpoint {

    private static final Logger LOG = LoggerFactory.getLogger(RmiEndpoint.class);
    static final long SESSION_TIMEOUT_SECONDS = 30;
    static final long MAX_POLL_MILLIS = 5_000;

    private final Address address;
    private final TransportContext context;
    private final Registry registry;
    private final boolean ownRegistry;
    private final SecureRandom random = new SecureRandom();
    private final Map<Long, RmiSession> sessions = new ConcurrentHashMap<>();
    private final ScheduledExecutorService expiry;

    RmiEndpoint(Address address, TransportContext context, Registry registry, boolean ownRegistry) {
        this.address = address;
        this.context = context;
        this.registry = registry;
        this.ownRegistry = ownRegistry;
        this.expiry = Executors.newSingleThreadScheduledExecutor(context.threads("rmi-sessions-" + address.port()));
        expiry.scheduleWithFixedDelay(io.robomw.agents.net.OwnerThreads.rounds(context.failures(), this::expire), 5, 5, TimeUnit.SECONDS);
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public long open(String peerName) throws RemoteException {
        int max = context.settings().limits().maxConnections();
        if (peerName == null || peerName.length() > 256) {
            peerName = peerName == null ? "?" : peerName.substring(0, 256) + "...";
        }
        if (sessions.size() >= max) {
            String why = "node '" + context.nodeName() + "' at " + address + " serves at most " + max
                    + " sessions (maxConnections) and has that many; try again later";
            context.dropped(DropReason.LIMIT, "rmi-session:" + peerName, "session refused: " + max + " sessions are open (maxConnections)");
            throw new RemoteException(why);
        }
        long id = random.nextLong();
        String host;
        try {
            host = RemoteServer.getClientHost();
        } catch (ServerNotActiveException e) {
            host = "local";
        }
        String peer = "rmi-session:" + peerName + "@" + host + "/" + Long.toHexString(id).substring(0, 6);
        OutboundBuffer outbound = new OutboundBuffer(peer, context.settings().outboundBufferBytes(), context.settings().sendTimeout().toNanos());
        RmiSession session = new RmiSession(id, peer, outbound, closed -> {
            sessions.remove(closed.id());
            context.closed(closed);
        });
        sessions.put(id, session);
        context.opened(session);
        return id;
    }

    @Override
    public void deliver(long session, byte[] frames) throws RemoteException {
        RmiSession s = session(session);
        s.delivering(Thread.currentThread());
        try {
            FrameBatches.deliver(frames, s, context);
        } finally {
            s.delivering(null);
        }
    }

    @Override
    public byte[] poll(long session, long maxWaitMillis) throws RemoteException {
        RmiSession s = session(session);
        s.polled();
        try {
            byte[] frames = s.outbound().take(TimeUnit.MILLISECONDS.toNanos(Math.max(0, Math.min(maxWaitMillis, MAX_POLL_MILLIS))));
            s.polled();
            return frames;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return new byte[0];
        }
    }

    @Override
    public void close(long session) {
        RmiSession s = sessions.get(session);
        if (s != null) {
            s.close();
        }
    }

    @Override
    public void close() {
        expiry.shutdownNow();
        sessions.values().forEach(RmiSession::close);
        try {
            registry.unbind(address.path());
        } catch (Exception e) {
            LOG.debug("unbinding {}: {}", address, e.toString());
        }
        try {
            UnicastRemoteObject.unexportObject(this, true);
        } catch (NoSuchObjectException e) {
            LOG.debug("unexporting {}: {}", address, e.toString());
        }
        if (ownRegistry) {
            try {
                UnicastRemoteObject.unexportObject(registry, true);
            } catch (NoSuchObjectException e) {
                LOG.debug("unexporting the registry of {}: {}", address, e.toString());
            }
        }
    }

    private RmiSession session(long id) throws NoSuchObjectException {
        RmiSession s = sessions.get(id);
        if (s == null) {
            throw new NoSuchObjectException("no session " + Long.toHexString(id) + " at " + address + " (it expired or the server restarted); reconnect");
        }
        return s;
    }

    private void expire() {
        long now = System.nanoTime();
        for (RmiSession s : sessions.values()) {
            if (now - s.lastPollNanos() > TimeUnit.SECONDS.toNanos(SESSION_TIMEOUT_SECONDS)) {
                LOG.info("node '{}': closing {}: no poll for {} s", context.nodeName(), s.peer(), SESSION_TIMEOUT_SECONDS);
                s.close();
            }
        }
    }
}
