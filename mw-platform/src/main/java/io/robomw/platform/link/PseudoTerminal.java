package io.robomw.platform.link;

import com.sun.jna.Memory;
import com.sun.jna.Native;
import com.sun.jna.NativeLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.ReadWriteLock;
import java.util.concurrent.locks.ReentrantReadWriteLock;

/**
 * A pseudo-terminal pair made in-process through libc ({@code posix_openpt}, {@code grantpt},
 * {@code unlockpt}, {@code ptsname}), so brick emulators and tests need nothing installed (no
 * socat). The driver under test opens the slave, {@link #devicePath()}, as if it were a serial
 * port ({@link SerialLink}); the emulator talks through the master ({@link #read},
 * {@link #masterInput()}, {@link #masterOutput()}). Works on Linux and macOS; {@link #open()}
 * fails with an {@link IOException} elsewhere.
 *
 * <h2>Raw bytes</h2>
 * The line discipline is set raw ({@code cfmakeraw} on the slave), so every byte value passes
 * unchanged both ways: no CR/LF translation, no echo, no Ctrl-C or XON/XOFF handling.
 * jSerialComm sets raw mode again when it opens the slave.
 *
 * <h2>Decision: the pseudo-terminal keeps its own slave descriptor open</h2>
 * When no process has the slave open, Linux makes every read of the master fail with
 * {@code EIO} and {@code poll} report {@code POLLHUP} without end, so an emulator whose driver
 * closes and reopens the port would spin or give up. This class opens the slave itself and keeps
 * it open until {@link #close()}. Consequences:
 * <ul>
 *   <li>the emulator survives any number of driver closes and reopens, and the device path stays
 *       the same;</li>
 *   <li>the emulator cannot tell that the driver has closed the port;</li>
 *   <li>bytes written to the master while no driver has the port open wait in the slave's input
 *       queue for the next driver, unless that driver flushes on open (jSerialComm does not);</li>
 *   <li>the raw settings persist from one driver open to the next.</li>
 * </ul>
 *
 * <h2>Closing</h2>
 * {@link #close()} closes the master. The kernel then hangs up the slave: the driver's reads fail
 * (jSerialComm returns -1, {@link SerialLink} throws {@link LinkLostException}) and its writes fail
 * with {@code EIO}. A read or write of the master blocked in another thread is woken through a
 * pipe: reads of {@link #masterInput()} return end of stream, {@link #read} and writes throw.
 *
 * <h2>Threads</h2>
 * One thread may read the master while another writes it; {@link #close()} may be called from any
 * thread. The master descriptor is non-blocking; waits happen in {@code poll(2)}.
 */
public final class PseudoTerminal implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(PseudoTerminal.class);

    /** Returned by the internal read when the pseudo-terminal was closed. */
    private static final int CLOSED = -1;

    private final Posix.LibC libc;
    private final int master;
    private final int slave;
    private final int wakeRead;
    private final int wakeWrite;
    private final String devicePath;
    private final AtomicBoolean closed = new AtomicBoolean();
    /** I/O holds the read lock while it uses the descriptors; close holds the write lock to close them. */
    private final ReadWriteLock lock = new ReentrantReadWriteLock();
    private final InputStream input = new MasterInput();
    private final OutputStream output = new MasterOutput();

    private PseudoTerminal(Posix.LibC libc, int master, int slave, int[] wake, String devicePath) {
        this.libc = libc;
        this.master = master;
        this.slave = slave;
        this.wakeRead = wake[0];
        this.wakeWrite = wake[1];
        this.devicePath = devicePath;
    }

    /**
     * Creates a pseudo-terminal pair in raw mode.
     *
     * @return the open pseudo-terminal
     * @throws IOException if this is not Linux or macOS, or a libc call fails (the message names it and errno)
     */
    public static PseudoTerminal open() throws IOException {
        Posix.LibC libc = Posix.libc();
        int master = Posix.check(libc.posix_openpt(Posix.O_RDWR | Posix.O_NOCTTY), "posix_openpt");
        int slave = -1;
        int[] wake = {-1, -1};
        try {
            Posix.check(libc.grantpt(master), "grantpt");
            Posix.check(libc.unlockpt(master), "unlockpt");
            String path = slaveName(libc, master);
            slave = Posix.check(libc.open(path, Posix.O_RDWR | Posix.O_NOCTTY), "open(" + path + ")");
            makeRaw(libc, slave);
            int flags = Posix.check(libc.fcntl(master, Posix.F_GETFL), "fcntl(F_GETFL)");
            Posix.check(libc.fcntl(master, Posix.F_SETFL, flags | Posix.O_NONBLOCK), "fcntl(F_SETFL)");
            Posix.check(libc.pipe(wake), "pipe");
            PseudoTerminal pty = new PseudoTerminal(libc, master, slave, wake, path);
            LOG.debug("opened pseudo-terminal {} (master fd {}, slave fd {})", path, master, slave);
            return pty;
        } catch (IOException | RuntimeException e) {
            for (int fd : new int[] {wake[0], wake[1], slave, master}) {
                if (fd >= 0) {
                    libc.close(fd);
                }
            }
            throw e;
        }
    }

    /** {@code ptsname} returns a static buffer, so calls are serialised. */
    private static String slaveName(Posix.LibC libc, int master) throws IOException {
        synchronized (PseudoTerminal.class) {
            String name = libc.ptsname(master);
            if (name == null) {
                throw new IOException("ptsname returned no device name for the new pseudo-terminal");
            }
            return name;
        }
    }

    private static void makeRaw(Posix.LibC libc, int fd) throws IOException {
        Memory termios = new Memory(Posix.TERMIOS_SIZE);
        termios.clear();
        Posix.check(libc.tcgetattr(fd, termios), "tcgetattr");
        libc.cfmakeraw(termios);
        Posix.check(libc.tcsetattr(fd, Posix.TCSANOW, termios), "tcsetattr");
    }

    /** @return the slave device, e.g. {@code /dev/pts/5}, which a driver opens as its serial port */
    public String devicePath() {
        return devicePath;
    }

    /**
     * @return a stream of the bytes the driver writes; {@code read} blocks until at least one byte
     *         arrives and returns end of stream once this pseudo-terminal is closed. Closing the
     *         stream does nothing; close the pseudo-terminal.
     */
    public InputStream masterInput() {
        return input;
    }

    /**
     * @return a stream to the driver; {@code write} blocks while the driver does not read and the
     *         buffer is full, and throws once this pseudo-terminal is closed. Closing the stream
     *         does nothing; close the pseudo-terminal.
     */
    public OutputStream masterOutput() {
        return output;
    }

    /**
     * Reads what the driver wrote, waiting up to {@code timeout} for the first byte.
     *
     * @param buf     where the bytes go
     * @param off     the first index to fill
     * @param len     the most bytes to read
     * @param timeout how long to wait; zero takes only what has already arrived
     * @return bytes read (at least 1), or 0 if none arrived in time (or {@code len} is 0)
     * @throws IOException if this pseudo-terminal is closed, or the read fails
     */
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Objects.checkFromIndexSize(off, len, buf.length);
        int n = readMaster(buf, off, len, Deadline.after(timeout));
        if (n == CLOSED) {
            throw closedException();
        }
        return n;
    }

    /** @param deadline when to give up, or {@code null} to wait for ever */
    private int readMaster(byte[] buf, int off, int len, Deadline deadline) throws IOException {
        if (len == 0) {
            return 0;
        }
        lock.readLock().lock();
        try {
            Memory chunk = new Memory(len);
            while (!closed.get()) {
                long n = libc.read(master, chunk, new NativeLong(len)).longValue();
                if (n > 0) {
                    chunk.read(0, buf, off, (int) n);
                    return (int) n;
                }
                int errno = Native.getLastError();
                if (n == 0 || (errno != Posix.EAGAIN && errno != Posix.EINTR)) {
                    throw n == 0 ? new IOException(devicePath + ": the master reached end of file")
                            : Posix.error("read of the pseudo-terminal master " + devicePath, errno);
                }
                if (deadline != null && deadline.expired()) {
                    return 0;
                }
                if (!await(Posix.POLLIN, deadline)) {
                    return CLOSED;
                }
            }
            return CLOSED;
        } finally {
            lock.readLock().unlock();
        }
    }

    private void writeMaster(byte[] data, int off, int len) throws IOException {
        Objects.checkFromIndexSize(off, len, data.length);
        if (len == 0) {
            return;
        }
        lock.readLock().lock();
        try {
            Memory chunk = new Memory(len);
            chunk.write(0, data, off, len);
            long done = 0;
            while (done < len) {
                if (closed.get()) {
                    throw closedException();
                }
                long n = libc.write(master, chunk.share(done), new NativeLong(len - done)).longValue();
                if (n >= 0) {
                    done += n;
                    continue;
                }
                int errno = Native.getLastError();
                if (errno != Posix.EAGAIN && errno != Posix.EINTR) {
                    throw Posix.error("write to the pseudo-terminal master " + devicePath, errno);
                }
                if (!await(Posix.POLLOUT, null)) {
                    throw closedException();
                }
            }
        } finally {
            lock.readLock().unlock();
        }
    }

    /**
     * Waits in {@code poll(2)} until the master is ready for {@code events}, the deadline passes, or
     * {@link #close()} writes to the wake pipe.
     *
     * @return {@code false} if woken because the pseudo-terminal is closing
     */
    private boolean await(short events, Deadline deadline) throws IOException {
        Memory fds = new Memory(2L * Posix.POLLFD_SIZE);
        Posix.setPollFd(fds, 0, master, events);
        Posix.setPollFd(fds, 1, wakeRead, Posix.POLLIN);
        int timeout = deadline == null ? -1 : deadline.remainingMillisRoundedUp();
        int ready = libc.poll(fds, new NativeLong(2), timeout);
        if (ready < 0) {
            int errno = Native.getLastError();
            if (errno != Posix.EINTR) {
                throw Posix.error("poll of the pseudo-terminal master " + devicePath, errno);
            }
        }
        return Posix.revents(fds, 1) == 0 && !closed.get();
    }

    private IOException closedException() {
        return new IOException("pseudo-terminal " + devicePath + " is closed");
    }

    /**
     * Closes the master, which hangs up the driver's side, then the slave descriptor kept by this
     * class. Wakes and ends reads and writes in progress. Idempotent.
     */
    @Override
    public void close() {
        if (!closed.compareAndSet(false, true)) {
            return;
        }
        Memory one = new Memory(1);
        one.setByte(0, (byte) 1);
        libc.write(wakeWrite, one, new NativeLong(1));
        lock.writeLock().lock();
        try {
            for (int fd : new int[] {master, slave, wakeRead, wakeWrite}) {
                if (libc.close(fd) != 0) {
                    LOG.debug("{}: closing fd {} failed, errno {}", devicePath, fd, Native.getLastError());
                }
            }
        } finally {
            lock.writeLock().unlock();
        }
        LOG.debug("closed pseudo-terminal {}", devicePath);
    }

    @Override
    public String toString() {
        return "PseudoTerminal[" + devicePath + (closed.get() ? ", closed]" : "]");
    }

    private final class MasterInput extends InputStream {
        @Override
        public int read() throws IOException {
            byte[] one = new byte[1];
            int n = read(one, 0, 1);
            return n < 0 ? -1 : one[0] & 0xFF;
        }

        @Override
        public int read(byte[] b, int off, int len) throws IOException {
            Objects.checkFromIndexSize(off, len, b.length);
            return readMaster(b, off, len, null);
        }
    }

    private final class MasterOutput extends OutputStream {
        @Override
        public void write(int b) throws IOException {
            writeMaster(new byte[] {(byte) b}, 0, 1);
        }

        @Override
        public void write(byte[] b, int off, int len) throws IOException {
            writeMaster(b, off, len);
        }
    }
}
