package io.robomw.platform.mavlink.link;

import io.robomw.platform.link.SerialLink;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameDecoder;

import java.io.IOException;
import java.net.SocketAddress;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * MAVLink over a serial port: a telemetry radio (SiK, RFD900) or a flight controller's USB port,
 * at {@value #DEFAULT_BAUD} baud 8N1 by default (the radios' air and serial default), opened
 * through jSerialComm as the bricks' serial links are ({@link SerialLink}). The byte stream is cut
 * into frames by one decoder; a false start byte holds the frames behind it until its claimed
 * length has come (at most 280 bytes, under 50 ms at 57600 baud).
 *
 * <p>A port that vanishes (a radio unplugged) makes {@link #receive} and {@link #send} throw
 * {@link io.robomw.platform.link.LinkLostException}; {@link #reopen()} tries again.
 *
 * <p>Threads: one receiver; {@link #send} from any thread (writes are serialised).
 */
public final class SerialMavlinkLink implements MavlinkLink {

    /** The telemetry radios' default baud rate. */
    public static final int DEFAULT_BAUD = 57_600;

    private final SerialLink port;
    private final FrameDecoder decoder;
    private final List<Frame> received = new ArrayList<>();
    private final byte[] buffer = new byte[4096];
    private final Object writeLock = new Object();
    private final PortAddress address;

    /** A serial port as the origin of frames. */
    private static final class PortAddress extends SocketAddress {
        private static final long serialVersionUID = 1L;
        private final String device;

        PortAddress(String device) {
            this.device = device;
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof PortAddress p && p.device.equals(device);
        }

        @Override
        public int hashCode() {
            return device.hashCode();
        }

        @Override
        public String toString() {
            return "serial " + device;
        }
    }

    private SerialMavlinkLink(SerialLink port) {
        this.port = port;
        this.decoder = new FrameDecoder(received::add);
        this.address = new PortAddress(port.devicePath());
    }

    /**
     * Opens a serial port.
     *
     * @param device the device ({@code /dev/ttyUSB0}, a pseudo-terminal's {@code /dev/pts/5})
     * @param baud   the baud rate
     * @return the open link
     * @throws IOException naming the device if it cannot be opened
     */
    public static SerialMavlinkLink open(String device, int baud) throws IOException {
        SerialLink link = new SerialLink(Objects.requireNonNull(device, "device"), SerialSettings.of(baud, 8, SerialSettings.Parity.NONE, 1));
        link.open();
        return new SerialMavlinkLink(link);
    }

    /**
     * Closes the port and opens it again (after it was lost); a partial frame is forgotten.
     *
     * @throws IOException naming the device if it cannot be opened
     */
    public void reopen() throws IOException {
        port.close();
        decoder.reset();
        port.open();
    }

    @Override
    public boolean send(byte[] frame) throws IOException {
        synchronized (writeLock) {
            port.write(frame, 0, frame.length);
        }
        return true;
    }

    @Override
    public int receive(Duration timeout, FrameSink sink) throws IOException {
        int n = port.read(buffer, 0, buffer.length, timeout);
        if (n <= 0) {
            return 0;
        }
        received.clear();
        decoder.feed(buffer, 0, n);
        int frames = received.size();
        for (Frame f : List.copyOf(received)) {
            sink.frame(f, address);
        }
        return frames;
    }

    /** @return the decoder's counts (frames, bad bytes) */
    public FrameDecoder.Counts counts() {
        return decoder.counts();
    }

    @Override
    public String describe() {
        return port.describe() + " at " + port.settings().baud() + " baud";
    }

    @Override
    public void close() {
        port.close();
    }
}
