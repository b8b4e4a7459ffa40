package io.robomw.platform.link;

import com.sun.jna.Library;
import com.sun.jna.Memory;
import com.sun.jna.Native;
import com.sun.jna.NativeLong;
import com.sun.jna.Platform;
import com.sun.jna.Pointer;

import java.io.IOException;

/**
 * The few libc calls {@link PseudoTerminal} needs, bound through JNA, with their constants for
 * Linux and macOS. Calls return libc's result; {@link #check} turns -1 into an
 * {@link IOException} carrying errno and its text.
 *
 * <p>errno is read with {@link Native#getLastError()}, which JNA saves after every call, rather
 * than with {@code LastErrorException}, which also fires when a successful call left errno set.
 */
final class Posix {

    /** libc, mapped by name. Variadic functions are declared variadic so arm64 macOS passes them right. */
    interface LibC extends Library {
        int posix_openpt(int flags);

        int grantpt(int fd);

        int unlockpt(int fd);

        String ptsname(int fd);

        int open(String path, int flags, Object... mode);

        int close(int fd);

        NativeLong read(int fd, Pointer buf, NativeLong count);

        NativeLong write(int fd, Pointer buf, NativeLong count);

        int poll(Pointer fds, NativeLong nfds, int timeoutMillis);

        int pipe(int[] fds);

        int fcntl(int fd, int cmd, Object... arg);

        int tcgetattr(int fd, Pointer termios);

        int tcsetattr(int fd, int optionalActions, Pointer termios);

        void cfmakeraw(Pointer termios);

        String strerror(int errnum);
    }

    static final int O_RDWR = 2;
    static final int O_NOCTTY = Platform.isMac() ? 0x20000 : 0x100;
    static final int O_NONBLOCK = Platform.isMac() ? 0x4 : 0x800;
    static final int F_GETFL = 3;
    static final int F_SETFL = 4;
    static final int TCSANOW = 0;
    static final int EINTR = 4;
    static final int EAGAIN = Platform.isMac() ? 35 : 11;

    static final short POLLIN = 0x1;
    static final short POLLOUT = 0x4;

    /** {@code struct pollfd}: int fd, short events, short revents. */
    static final int POLLFD_SIZE = 8;
    private static final int POLLFD_EVENTS = 4;
    private static final int POLLFD_REVENTS = 6;

    /**
     * Room for {@code struct termios}, which is only passed through (60 bytes on Linux, 72 on
     * macOS), so its fields never need to be mapped.
     */
    static final int TERMIOS_SIZE = 256;

    private Posix() {
    }

    /**
     * @return libc
     * @throws IOException on systems other than Linux and macOS, or if libc cannot be loaded
     */
    static LibC libc() throws IOException {
        if (!Platform.isLinux() && !Platform.isMac()) {
            throw new IOException("pseudo-terminals need Linux or macOS, but this is "
                    + System.getProperty("os.name") + "; use a TCP link or real serial hardware instead");
        }
        try {
            return Holder.LIBC;
        } catch (LinkageError e) {
            throw new IOException("cannot load libc through JNA: " + e, e);
        }
    }

    /**
     * @param result a libc result
     * @param what   the call, for the message
     * @return the result, if it is not -1
     * @throws IOException naming the call, errno and its text
     */
    static int check(int result, String what) throws IOException {
        if (result == -1) {
            throw error(what, Native.getLastError());
        }
        return result;
    }

    /**
     * @param what  the call that failed
     * @param errno its errno
     * @return an exception naming both
     */
    static IOException error(String what, int errno) {
        return new IOException(what + " failed: errno " + errno + " (" + Holder.LIBC.strerror(errno) + ")");
    }

    /** Writes one {@code struct pollfd} at index {@code i}. */
    static void setPollFd(Memory fds, int i, int fd, short events) {
        fds.setInt((long) i * POLLFD_SIZE, fd);
        fds.setShort((long) i * POLLFD_SIZE + POLLFD_EVENTS, events);
        fds.setShort((long) i * POLLFD_SIZE + POLLFD_REVENTS, (short) 0);
    }

    /** @return the {@code revents} of the {@code struct pollfd} at index {@code i} */
    static short revents(Memory fds, int i) {
        return fds.getShort((long) i * POLLFD_SIZE + POLLFD_REVENTS);
    }

    /** Loaded on first use, so merely touching {@link Posix} on Windows does not load anything. */
    private static final class Holder {
        static final LibC LIBC = Native.load(Platform.C_LIBRARY_NAME, LibC.class);
    }
}
