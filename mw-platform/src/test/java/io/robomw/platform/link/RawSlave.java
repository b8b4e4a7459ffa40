package io.robomw.platform.link;

import com.sun.jna.Memory;
import com.sun.jna.Native;
import com.sun.jna.NativeLong;

import java.io.IOException;
import java.time.Duration;

/**
 * A pty slave opened straight through libc, so a test sees the pseudo-terminal's own line settings
 * rather than the ones jSerialComm applies when it opens a port.
 */
final class RawSlave implements AutoCloseable {

    private final Posix.LibC libc;
    private final int fd;

    private RawSlave(Posix.LibC libc, int fd) {
        this.libc = libc;
        this.fd = fd;
    }

    static RawSlave open(String path) throws IOException {
        Posix.LibC libc = Posix.libc();
        int fd = Posix.check(libc.open(path, Posix.O_RDWR | Posix.O_NOCTTY | Posix.O_NONBLOCK), "open " + path);
        return new RawSlave(libc, fd);
    }

    /** Writes all bytes; small writes to an empty pty never block. */
    void write(byte[] data) throws IOException {
        Memory m = new Memory(data.length);
        m.write(0, data, 0, data.length);
        long n = libc.write(fd, m, new NativeLong(data.length)).longValue();
        if (n != data.length) {
            throw new IOException("wrote " + n + " of " + data.length + " bytes, errno " + Native.getLastError());
        }
    }

    /** Waits in poll(2) up to {@code timeout}, then reads; 0 on timeout. */
    int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        Memory fds = new Memory(Posix.POLLFD_SIZE);
        Posix.setPollFd(fds, 0, fd, Posix.POLLIN);
        int ready = Posix.check(libc.poll(fds, new NativeLong(1),
                Deadline.after(timeout).remainingMillisRoundedUp()), "poll");
        if (ready == 0) {
            return 0;
        }
        Memory m = new Memory(len);
        long n = libc.read(fd, m, new NativeLong(len)).longValue();
        if (n < 0) {
            throw new IOException("read failed, errno " + Native.getLastError());
        }
        m.read(0, buf, off, (int) n);
        return (int) n;
    }

    @Override
    public void close() {
        libc.close(fd);
    }
}
