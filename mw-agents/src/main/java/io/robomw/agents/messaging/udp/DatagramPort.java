package io.robomw.agents.messaging.udp;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.MessagingSettings;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.spi.TransportContext;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.SocketAddress;
import java.nio.ByteBuffer;
import java.nio.channels.ClosedChannelException;
import java.nio.channels.DatagramChannel;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Function;

/**
 * One bound datagram socket: a reader thread hands each datagram (one frame) to the node, and
 * {@link #send} numbers frames per destination so receivers can count losses. A datagram is
 * never bigger than {@value MessagingSettings#MAX_DATAGRAM} bytes; larger frames are refused at
 * the sender. A bad datagram is dropped and the socket keeps serving every peer.
 *
 * <p>Thread-safe; the reader thread ends when the port is closed.
 */
public final class DatagramPort implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(DatagramPort.class);
    private static final int MAX_DESTINATIONS = 4096;
    /** How long {@link #close()} waits for the reader thread to leave {@code receive}. */
    private static final long CLOSE_WAIT_MILLIS = 5_000;

    private final DatagramChannel channel;
    private final TransportContext context;
    private final String label;
    private final Map<SocketAddress, AtomicLong> sequences = new ConcurrentHashMap<>();
    private final int maxFrame;
    private volatile Thread reader;

    /**
     * @param channel a bound channel
     * @param context the node
     * @param label   how logs name it, for example {@code udp://127.0.0.1:7000}
     */
    public DatagramPort(DatagramChannel channel, TransportContext context, String label) {
        this.channel = channel;
        this.context = context;
        this.label = label;
        this.maxFrame = Math.min(context.settings().maxFrameSize(), MessagingSettings.MAX_DATAGRAM);
    }

    /**
     * Starts the reader thread.
     *
     * @param peerOf makes the channel a datagram's answers go back on, from its source address
     */
    public void start(Function<InetSocketAddress, UdpPeer> peerOf) {
        Thread t = context.threads("read-" + label.replace("://", "-")).newThread(() -> readLoop(peerOf));
        reader = t;
        t.start();
    }

    /** @return the bound address */
    public InetSocketAddress localAddress() throws IOException {
        return (InetSocketAddress) channel.getLocalAddress();
    }

    /** @return the largest frame it sends or accepts */
    public int maxFrameBytes() {
        return maxFrame;
    }

    /** @return how logs name it */
    public String label() {
        return label;
    }

    /**
     * Sends one frame as one datagram, with the next stream sequence for that destination.
     *
     * @param frame an encoded frame (copied)
     * @param to    the destination
     * @throws IOException if the frame does not fit in a datagram or the send fails
     */
    public void send(byte[] frame, InetSocketAddress to) throws IOException {
        if (frame.length > maxFrame) {
            throw new IOException("a frame of " + frame.length + " bytes does not fit in one datagram to " + to
                    + " (limit " + maxFrame + " bytes); use tcp:// or rmi:// for large payloads");
        }
        if (sequences.size() > MAX_DESTINATIONS) {
            sequences.clear();
        }
        byte[] copy = frame.clone();
        FrameCodec.writeStreamSequence(copy, 0, sequences.computeIfAbsent(to, a -> new AtomicLong()).incrementAndGet());
        channel.send(ByteBuffer.wrap(copy), to);
    }

    /**
     * @param thread a thread
     * @return whether it is this port's reader
     */
    public boolean isReader(Thread thread) {
        return thread == reader;
    }

    /**
     * Closes the socket and waits (up to {@value #CLOSE_WAIT_MILLIS} ms) for the reader thread to end:
     * the kernel releases the port only once no thread is inside {@code receive} (the JDK defers the
     * real close until then), so a node bound to the same port right after this returns gets it.
     * Called on the reader thread itself (a listener closing its node), it does not wait.
     */
    @Override
    public void close() {
        try {
            channel.close();
        } catch (IOException e) {
            LOG.debug("closing {}: {}", label, e.toString());
        }
        Thread t = reader;
        if (t != null && t != Thread.currentThread()) {
            try {
                t.join(CLOSE_WAIT_MILLIS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            if (t.isAlive()) {
                LOG.warn("node '{}': the reader of {} did not end within {} ms of closing; its port may stay taken until it does",
                        context.nodeName(), label, CLOSE_WAIT_MILLIS);
            }
        }
    }

    private void readLoop(Function<InetSocketAddress, UdpPeer> peerOf) {
        ByteBuffer buf = ByteBuffer.allocateDirect(MessagingSettings.MAX_DATAGRAM + 1);
        while (channel.isOpen()) {
            InetSocketAddress from;
            byte[] datagram;
            try {
                buf.clear();
                from = (InetSocketAddress) channel.receive(buf);
                buf.flip();
                datagram = new byte[buf.remaining()];
                buf.get(datagram);
            } catch (ClosedChannelException e) {
                return;
            } catch (IOException e) {
                LOG.warn("node '{}': receiving on {} failed: {}", context.nodeName(), label, e.toString());
                continue;
            }
            if (datagram.length > maxFrame) {
                context.dropped(DropReason.OVERSIZED, from.toString(), "datagram of " + datagram.length + " bytes, above the limit of " + maxFrame);
                continue;
            }
            try {
                context.onFrame(datagram, 0, datagram.length, peerOf.apply(from));
            } catch (Throwable e) {
                context.failures().surviveOrRethrow(Thread.currentThread().getName(), e);
                LOG.warn("node '{}': a datagram from {} on {} could not be handled ({}); dropped, the node goes on", context.nodeName(), from, label,
                        e.toString());
            }
        }
    }
}
