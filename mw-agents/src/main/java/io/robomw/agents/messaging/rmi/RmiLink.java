package io.robomw.agents.messaging.rmi;

import io.robomw.agents.messaging.Address;
import io.robomw.agents.messaging.io.OutboundBuffer;
import io.robomw.agents.messaging.spi.Link;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.rmi.RemoteException;
import java.util.Arrays;
import java.util.concurrent.atomic.AtomicBoolean;

/**
 * The client side of the RMI transport: a session at a remote {@link FrameEndpoint}. Frames go
 * out through an {@link OutboundBuffer} whose writer thread delivers them in batches; a poller
 * thread fetches the frames waiting for this client and hands them to the node (listeners run on
 * it). A failed call closes the link; the node reconnects configured peers.
 */
final class RmiLink implements Link {

    private static final Logger LOG = LoggerFactory.getLogger(RmiLink.class);
    private static final long POLL_MILLIS = 1_000;

    private final Address address;
    private final FrameEndpoint remote;
    private final long session;
    private final TransportContext context;
    private final OutboundBuffer outbound;
    private final AtomicBoolean closed = new AtomicBoolean();
    private volatile Thread poller;

    private final java.util.function.Consumer<RmiLink> onClosed;

    RmiLink(Address address, FrameEndpoint remote, long session, TransportContext context, java.util.function.Consumer<RmiLink> onClosed) {
        this.onClosed = onClosed;
        this.address = address;
        this.remote = remote;
        this.session = session;
        this.context = context;
        this.outbound = new OutboundBuffer(address.toString(), context.settings().outboundBufferBytes(), context.settings().sendTimeout().toNanos());
    }

    void start() {
        String role = "rmi-" + address.port() + "-" + address.path();
        outbound.startWriter((b, o, l) -> {
            try {
                remote.deliver(session, o == 0 && l == b.length ? b : Arrays.copyOfRange(b, o, o + l));
            } catch (RemoteException e) {
                throw new IOException("delivering to " + address + " failed: " + io.robomw.agents.net.RmiSocketSetup.reason(e), e);
            }
        }, context.threads(role + "-deliver"), e -> fail(e.getMessage()));
        Thread t = context.threads(role + "-poll").newThread(this::pollLoop);
        poller = t;
        t.start();
        context.opened(this);
    }

    @Override
    public Address address() {
        return address;
    }

    @Override
    public String peer() {
        return address.toString();
    }

    @Override
    public void send(byte[] frame) throws IOException {
        outbound.send(frame);
    }

    @Override
    public boolean isOpen() {
        return !closed.get();
    }

    @Override
    public boolean isConnection() {
        return true;
    }

    @Override
    public boolean deliversOn(Thread thread) {
        return thread == poller;
    }

    @Override
    public boolean stuck(long nowNanos, long limitNanos) {
        return outbound.stuck(nowNanos, limitNanos);
    }

    @Override
    public void close() {
        if (closed.compareAndSet(false, true)) {
            outbound.close();
            if (Thread.currentThread() != poller) {
                outbound.awaitDrained(1_000_000_000L);
            }
            Thread t = poller;
            if (t != null && t != Thread.currentThread()) {
                t.interrupt();
            }
            try {
                remote.close(session);
            } catch (RemoteException e) {
                LOG.debug("closing session at {}: {}", address, e.toString());
            }
            onClosed.accept(this);
            context.closed(this);
        }
    }

    private void pollLoop() {
        while (!closed.get()) {
            byte[] frames;
            try {
                frames = remote.poll(session, POLL_MILLIS);
            } catch (RemoteException e) {
                fail("polling " + address + " failed: " + io.robomw.agents.net.RmiSocketSetup.reason(e));
                return;
            }
            try {
                FrameBatches.deliver(frames, this, context);
            } catch (Throwable e) {
                try {
                    context.failures().surviveOrRethrow(Thread.currentThread().getName(), e);
                } finally {
                    fail("frames could not be handled: " + e);
                }
                return;
            }
        }
    }

    private void fail(String why) {
        if (!closed.get()) {
            LOG.warn("node '{}': link to {}: {}", context.nodeName(), address, why);
        }
        close();
    }
}
