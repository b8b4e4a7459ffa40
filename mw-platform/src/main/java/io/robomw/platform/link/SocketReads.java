package io.robomw.platform.link;

import java.io.IOException;
import java.io.InputStream;
import java.net.Socket;
import java.net.SocketTimeoutException;

/** Timed reads from a connected socket, shared by the TCP links. */
final class SocketReads {

    private SocketReads() {
    }

    /**
     * Reads what has arrived, waiting until the deadline for the first byte.
     *
     * @param socket   the connected socket
     * @param buf      where the bytes go
     * @param off      the first index to fill
     * @param len      the most bytes to read, at least 1
     * @param deadline when to give up
     * @return bytes read (at least 1), 0 if none arrived in time, or -1 if the peer closed the connection
     * @throws IOException if the connection failed (reset) or the socket was closed
     */
    static int read(Socket socket, byte[] buf, int off, int len, Deadline deadline) throws IOException {
        InputStream in = socket.getInputStream();
        if (deadline.expired()) {
            int available = in.available();
            return available == 0 ? 0 : in.read(buf, off, Math.min(available, len));
        }
        // SO_TIMEOUT 0 would mean "forever": wait at least 1 ms.
        socket.setSoTimeout(Math.max(1, deadline.remainingMillisRoundedUp()));
        try {
            return in.read(buf, off, len);
        } catch (SocketTimeoutException e) {
            return 0;
        }
    }
}
