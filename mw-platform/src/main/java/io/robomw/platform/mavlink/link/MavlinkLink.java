package io.robomw.platform.mavlink.link;

import io.robomw.platform.mavlink.wire.Frame;

import java.io.IOException;
import java.net.SocketAddress;
import java.time.Duration;

/**
 * One MAVLink link: a UDP socket ({@link UdpMavlinkLink}) or a serial port with a telemetry radio
 * on it ({@link SerialMavlinkLink}). It carries whole frames: {@link #send} writes one encoded
 * frame, {@link #receive} cuts what arrives into frames with its own decoder (bad bytes are
 * skipped, never an error).
 *
 * <h2>Threads</h2>
 * One thread receives (the link's owner); any thread may send. {@link #close()} from any thread
 * ends a receive in progress.
 */
public interface MavlinkLink extends AutoCloseable {

    /** Receives the frames a link read. */
    @FunctionalInterface
    interface FrameSink {
        /**
         * @param frame a frame of a known message with a good checksum
         * @param from  where it came from (a UDP sender's address; for a serial port, the port)
         */
        void frame(Frame frame, SocketAddress from);
    }

    /**
     * Sends one frame.
     *
     * @param frame the frame's bytes
     * @return whether it went out; {@code false} when there is no one to send it to yet (a
     *         listening UDP link that has heard from nobody)
     * @throws IOException if the link failed or is closed
     */
    boolean send(byte[] frame) throws IOException;

    /**
     * Waits up to {@code timeout} for bytes and hands the frames they complete to the sink, on
     * this thread.
     *
     * @param timeout how long to wait when nothing has come
     * @param sink    receives the frames
     * @return how many frames were handed on (0 when nothing came in time)
     * @throws IOException if the link failed or is closed
     */
    int receive(Duration timeout, FrameSink sink) throws IOException;

    /** @return the link for messages, {@code "udp listening on 127.0.0.1:14550"} */
    String describe();

    /** Releases the socket or port. Idempotent; never throws. */
    @Override
    void close();
}
