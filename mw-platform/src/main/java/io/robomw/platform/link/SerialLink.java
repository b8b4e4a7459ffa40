package io.robomw.platform.link;

import com.fazecast.jSerialComm.SerialPort;
import com.fazecast.jSerialComm.SerialPortInvalidPortException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.locks.ReadWriteLock;
import java.util.concurrent.locks.ReentrantReadWriteLock;

/**
 * A {@link Link} over a serial port, opened by device path through jSerialComm, so a
 * pseudo-terminal ({@link PseudoTerminal#devicePath()}) or a symbolic link such as
 * {@code /dev/serial/by-id/...} works as well as {@code /dev/ttyUSB0}. The path is resolved again
 * on every {@link #open()}, so a symbolic link that now points at a new device is followed.
 *
 * <h2>Timeouts</h2>
 * The port reads "semi-blocking": jSerialComm maps this to termios {@code VMIN=0, VTIME=1}, so
 * each native read returns as soon as a byte is there, or after {@value #READ_SLICE_MILLIS} ms.
 * {@link #read} repeats such slices until its deadline, so it returns at once when bytes arrive
 * and otherwise waits at least the timeout and at most about {@value #READ_SLICE_MILLIS} ms more
 * (POSIX counts {@code VTIME} in tenths of a second). A zero timeout takes only what is there.
 *
 * <h2>A lost port</h2>
 * jSerialComm's read returns -1 when the device hung up (a pty master closed, a USB adapter was
 * unplugged) and its write returns -1 when the device is gone; both become
 * {@link LinkLostException}. The link then stays open until {@link #close()}.
 *
 * <h2>Closing</h2>
 * {@link #close()} always calls {@code SerialPort.closePort()}, which releases the exclusive lock
 * jSerialComm holds on the device; a port left open cannot be opened again in the same JVM
 * (jSerialComm issue #159). Closing waits for a read slice in progress to end (at most
 * {@value #READ_SLICE_MILLIS} ms) and for a write in progress. Note that jSerialComm's close
 * flushes both queues ({@code tcflush(TCIOFLUSH)}); on a pty this also discards bytes this side
 * wrote that the master has not read yet.
 *
 * <p>Threads: as {@link Link} says, one reader and one writer at a time; open and close from any
 * thread.
 */
public final class SerialLink implements Link {

    private static final Logger LOG = LoggerFactory.getLogger(SerialLink.class);

    /** Length of one native read, the granularity of read timeouts (termios VTIME = 1). */
    static final int READ_SLICE_MILLIS = 100;

    private final String devicePath;
    private final SerialSettings settings;
    /** Read/write hold the read lock during a native call; open/close hold the write lock. */
    private final ReadWriteLock lock = new ReentrantReadWriteLock();
    private volatile SerialPort port;

    /**
     * Creates a closed link.
     *
     * @param devicePath the device, e.g. {@code /dev/ttyUSB0} or a pty's {@code /dev/pts/5}
     * @param settings   the line settings
     */
    public SerialLink(String devicePath, SerialSettings settings) {
        this.devicePath = Objects.requireNonNull(devicePath, "devicePath");
        this.settings = Objects.requireNonNull(settings, "settings");
    }

    /** @return the device path this link opens */
    public String devicePath() {
        return devicePath;
    }

    /** @return the line settings */
    public SerialSettings settings() {
        return settings;
    }

    @Override
    public void open() throws IOException {
        lock.writeLock().lock();
        try {
            if (port != null) {
                return;
            }
            SerialPort candidate;
            try {
                candidate = SerialPort.getCommPort(devicePath);
            } catch (SerialPortInvalidPortException e) {
                throw new IOException("cannot open " + describe() + ": no such device", e);
            }
            candidate.setComPortParameters(settings.baud(), settings.dataBits(), stopBits(), parity());
            candidate.setFlowControl(SerialPort.FLOW_CONTROL_DISABLED);
            candidate.setComPortTimeouts(SerialPort.TIMEOUT_READ_SEMI_BLOCKING, READ_SLICE_MILLIS, 0);
            if (!candidate.openPort()) {
                throw new IOException(String.format(
                        "cannot open %s (%s): error %d at jSerialComm native line %d; "
                                + "errno 2 = no such device, 13 = no permission, 11 or 35 = in use by another process",
                        describe(), candidate.getSystemPortPath(), candidate.getLastErrorCode(),
                        candidate.getLastErrorLocation()));
            }
            port = candidate;
            LOG.debug("opened {} ({}) at {}", describe(), candidate.getSystemPortPath(), settings);
        } finally {
            lock.writeLock().unlock();
        }
    }

    @Override
    public boolean isOpen() {
        return port != null;
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        Objects.checkFromIndexSize(off, len, data.length);
        if (len == 0) {
            return;
        }
        lock.readLock().lock();
        try {
            SerialPort p = openPort();
            int written = p.writeBytes(data, len, off);
            if (written != len) {
                throw new LinkLostException(describe(), String.format(
                        "write failed after %d of %d bytes; the port hung up or vanished%s",
                        Math.max(written, 0), len, errorCode(p)));
            }
        } finally {
            lock.readLock().unlock();
        }
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Objects.checkFromIndexSize(off, len, buf.length);
        Deadline deadline = Deadline.after(timeout);
        if (len == 0) {
            return 0;
        }
        if (timeout.isZero()) {
            return readAvailable(buf, off, len);
        }
        while (true) {
            int n = readSlice(buf, off, len);
            if (n > 0 || deadline.expired()) {
                return n;
            }
        }
    }

    /** One native read of at most {@value #READ_SLICE_MILLIS} ms. */
    private int readSlice(byte[] buf, int off, int len) throws IOException {
        lock.readLock().lock();
        try {
            SerialPort p = openPort();
            int n = p.readBytes(buf, len, off);
            if (n < 0) {
                throw lost(p);
            }
            return n;
        } finally {
            lock.readLock().unlock();
        }
    }

    private int readAvailable(byte[] buf, int off, int len) throws IOException {
        lock.readLock().lock();
        try {
            SerialPort p = openPort();
            int available = p.bytesAvailable();
            if (available < 0) {
                throw lost(p);
            }
            if (available == 0) {
                return 0;
            }
            int n = p.readBytes(buf, Math.min(available, len), off);
            if (n < 0) {
                throw lost(p);
            }
            return n;
        } finally {
            lock.readLock().unlock();
        }
    }

    private LinkLostException lost(SerialPort p) {
        return new LinkLostException(describe(), "read failed: the port hung up or vanished" + errorCode(p));
    }

    /** jSerialComm's last errno, when it recorded one (a hung-up read returns 0 and leaves none). */
    private static String errorCode(SerialPort p) {
        int code = p.getLastErrorCode();
        return code == 0 ? "" : " (errno " + code + ")";
    }

    private SerialPort openPort() throws IOException {
        SerialPort p = port;
        if (p == null) {
            throw new IOException(describe() + " is closed");
        }
        return p;
    }

    @Override
    public String describe() {
        return "serial " + devicePath;
    }

    @Override
    public void close() {
        lock.writeLock().lock();
        try {
            SerialPort p = port;
            if (p == null) {
                return;
            }
            port = null;
            if (!p.closePort()) {
                LOG.warn("{}: jSerialComm could not close the port (error {})", describe(), p.getLastErrorCode());
            }
            LOG.debug("closed {}", describe());
        } finally {
            lock.writeLock().unlock();
        }
    }

    private int stopBits() {
        return settings.stopBits() == 2 ? SerialPort.TWO_STOP_BITS : SerialPort.ONE_STOP_BIT;
    }

    private int parity() {
        return switch (settings.parity()) {
            case NONE -> SerialPort.NO_PARITY;
            case ODD -> SerialPort.ODD_PARITY;
            case EVEN -> SerialPort.EVEN_PARITY;
            case MARK -> SerialPort.MARK_PARITY;
            case SPACE -> SerialPort.SPACE_PARITY;
        };
    }

    @Override
    public String toString() {
        return describe();
    }
}
