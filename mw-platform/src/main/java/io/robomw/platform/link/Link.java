package io.robomw.platform.link;

import java.io.IOException;
import java.time.Duration;

/**
 * One byte stream to a brick: a serial port ({@link SerialLink}) or a TCP connection
 * ({@link TcpClientLink}, {@link TcpServerLink}). A link moves bytes only; framing belongs to the
 * brick's codec, and {@link Communicator} adds deadlines over whole frames, wire logging and
 * lost/restored events.
 *
 * <h2>Life cycle</h2>
 * A link is created closed. {@link #open()} acquires the port or connection; {@link #close()}
 * releases it and may be called any number of times; a closed link can be opened again. A link
 * whose peer went away stays open (its transfers throw {@link LinkLostException}) until it is
 * closed.
 *
 * <h2>Threads</h2>
 * Implementations allow one thread in {@link #read} and another in {@link #write} at the same
 * time. {@link #open()} and {@link #close()} may be called from any thread; a read or write that
 * is in progress then ends with an {@link IOException} saying the link is closed.
 */
public interface Link extends AutoCloseable {

    /**
     * Acquires the port or connection. Does nothing if the link is already open.
     *
     * @throws IOException if the port cannot be opened or the peer cannot be reached; the message
     *                     names the link and the reason
     */
    void open() throws IOException;

    /** @return whether {@link #open()} succeeded and {@link #close()} has not been called since */
    boolean isOpen();

    /**
     * Writes all {@code len} bytes, blocking while the operating system's buffer is full.
     *
     * @param data the bytes
     * @param off  the first byte to write
     * @param len  how many bytes to write
     * @throws LinkLostException if the peer hung up or the port vanished
     * @throws IOException       if the link is closed
     */
    void write(byte[] data, int off, int len) throws IOException;

    /**
     * Reads whatever has arrived, waiting up to {@code timeout} for the first byte. Never reads
     * more than {@code len} bytes, so bytes beyond a requested frame stay for the next read.
     *
     * @param buf     where the bytes go
     * @param off     the first index to fill
     * @param len     the most bytes to read
     * @param timeout how long to wait for the first byte; zero takes only what has already arrived
     * @return how many bytes were read, at least 1, or 0 if none arrived in time (or {@code len} is 0)
     * @throws LinkLostException if the peer hung up or the port vanished
     * @throws IOException       if the link is closed
     */
    int read(byte[] buf, int off, int len, Duration timeout) throws IOException;

    /** @return the link for messages and logs, e.g. {@code "serial /dev/pts/5"} or {@code "tcp 127.0.0.1:65000"} */
    String describe();

    /** Releases the port or connection. Idempotent; never throws. */
    @Override
    void close();
}
