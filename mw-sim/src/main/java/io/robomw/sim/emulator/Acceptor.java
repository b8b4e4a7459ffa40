package io.robomw.sim.emulator;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;

import java.io.IOException;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketTimeoutException;

/**
 * An emulator's accepting thread: takes one connection per round off a listening socket and hands
 * it over, on an {@link OwnerThread} whose failures go to the emulator's {@link FailurePolicy}
 * (a failed accept, or a connection that could not be handed over, is reported and the next is
 * accepted). Each accept waits at most {@value #ACCEPT_POLL_MILLIS} ms. Closing the socket, then
 * the thread, ends it.
 */
public final class Acceptor implements OwnerThread.Duty {

    /** The longest one accept waits, milliseconds. */
    static final int ACCEPT_POLL_MILLIS = 200;

    /** What is done with an accepted connection. */
    @FunctionalInterface
    public interface Handler {
        /**
         * @param peer the connection, now the handler's to close
         * @throws IOException if it cannot be served (the connection is then closed)
         */
        void accepted(Socket peer) throws IOException;
    }

    private final ServerSocket server;
    private final Handler handler;

    private Acceptor(ServerSocket server, Handler handler) {
        this.server = server;
        this.handler = handler;
    }

    /**
     * Starts accepting.
     *
     * @param role     the thread's name ({@code emulator-aibo-<robot>})
     * @param server   the bound socket
     * @param handler  what is done with each connection
     * @param failures where failures go
     * @return the thread, to close after the socket
     * @throws IOException if the socket's accept timeout cannot be set
     */
    public static OwnerThread start(String role, ServerSocket server, Handler handler, FailurePolicy failures) throws IOException {
        server.setSoTimeout(ACCEPT_POLL_MILLIS);
        return OwnerThread.start(role, Thread.NORM_PRIORITY, new Acceptor(server, handler), EmulatorThreads.BACK_OFF, failures);
    }

    /** @return 1: a connection was accepted, or the poll interval passed; 0 once the socket is closed */
    @Override
    public int doWork() throws IOException {
        if (server.isClosed()) {
            return 0;
        }
        Socket peer;
        try {
            peer = server.accept();
        } catch (SocketTimeoutException e) {
            return 1;
        } catch (IOException e) {
            if (server.isClosed()) {
                return 0;
            }
            throw e;
        }
        try {
            handler.accepted(peer);
        } catch (Throwable e) {
            try {
                peer.close();
            } catch (IOException ignored) {
                // the connection is given up either way
            }
            throw e;
        }
        return 1;
    }
}
