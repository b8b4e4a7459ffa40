package io.robomw.agents.host;

import io.robomw.agents.host.rmi.HostConnections;
import io.robomw.agents.host.rmi.HostSockets;
import org.junit.jupiter.api.Test;

import java.io.BufferedInputStream;
import java.io.BufferedOutputStream;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class HostSocketsTest {

    /** What RMI's client transport does: buffered streams over the factory's socket. */
    @Test
    void aPingRightAfterAnAnswerIsAnsweredWithoutGoingToTheServerAndOtherBytesPass() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            HostSockets.Client factory = new HostSockets.Client("127.0.0.1", false, 5_000);
            try (Socket client = factory.createSocket("ignored", server.getLocalPort()); Socket peer = server.accept()) {
                OutputStream out = new BufferedOutputStream(client.getOutputStream());
                InputStream in = new BufferedInputStream(client.getInputStream());
                InputStream peerIn = peer.getInputStream();
                OutputStream peerOut = peer.getOutputStream();

                // No answer yet: a ping goes to the server, which answers it.
                out.write(HostSockets.RMI_PING);
                out.flush();
                assertEquals(HostSockets.RMI_PING, peerIn.read());
                peerOut.write(HostSockets.RMI_PING_ACK);
                assertEquals(HostSockets.RMI_PING_ACK, in.read());

                // A call and its answer.
                out.write(new byte[] {0x50, 1, 2, 3});
                out.flush();
                assertEquals(0x50, peerIn.read());
                assertEquals(3, peerIn.readNBytes(3).length);
                peerOut.write(new byte[] {0x51, 9});
                assertEquals(0x51, in.read());
                assertEquals(9, in.read());

                // A ping right after that answer is answered here; the next call reaches the server first.
                out.write(HostSockets.RMI_PING);
                out.flush();
                assertEquals(HostSockets.RMI_PING_ACK, in.read());
                assertEquals(1, ((HostSockets.WarmSocket) client).pingsAnswered());
                out.write(new byte[] {0x50, 7});
                out.flush();
                assertEquals(0x50, peerIn.read());
                assertEquals(7, peerIn.read());

                // A 0x52 that is not the first write after an answer (inside a call) passes untouched.
                out.write(HostSockets.RMI_PING);
                out.flush();
                assertEquals(HostSockets.RMI_PING, peerIn.read());
            }
        }
    }

    /**
     * A plain endpoint keeps at most MAX_CONNECTIONS; one more makes the oldest that has proved
     * nothing make way (it is closed), so idle connections cannot lock peers out.
     */
    @Test
    void aConnectionBeyondTheLimitMakesTheOldestThatProvedNothingMakeWay() throws Exception {
        HostSockets.Counters counters = new HostSockets.Counters();
        HostConnections connections = new HostConnections("limits", 0);
        java.util.List<Socket> held = new java.util.ArrayList<>();
        try (ServerSocket server = new HostSockets.Server(InetAddress.getLoopbackAddress(), null, counters, connections, 0).createServerSocket(0)) {
            for (int i = 0; i < HostSockets.MAX_CONNECTIONS; i++) {
                held.add(new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort()));
                held.add(server.accept());
            }
            try (Socket extra = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort())) {
                held.add(server.accept());
                Socket oldest = held.get(0);
                oldest.setSoTimeout(10_000);
                assertEquals(-1, oldest.getInputStream().read(), "the oldest connection, which proved nothing, was closed");
                assertEquals(1, connections.evicted());
                assertEquals(0, counters.refused.sum(), "the new one was taken");
                assertEquals(HostSockets.MAX_CONNECTIONS, counters.open.get());
                assertEquals(HostSockets.MAX_CONNECTIONS, connections.open());
            }
        } finally {
            for (Socket s : held) {
                s.close();
            }
        }
    }

    /** A TLS endpoint keeps the same limit: connections are counted before their handshake, and the oldest makes way at once. */
    @Test
    void aTlsConnectionBeyondTheLimitMakesTheOldestThatProvedNothingMakeWay(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir) throws Exception {
        javax.net.ssl.SSLContext tls = io.robomw.agents.messaging.TestKeys.create(dir).node().context();
        HostSockets.Counters counters = new HostSockets.Counters();
        HostConnections connections = new HostConnections("limits", 0);
        java.util.List<Socket> held = new java.util.ArrayList<>();
        try (ServerSocket server = new HostSockets.Server(InetAddress.getLoopbackAddress(), tls, counters, connections, 0).createServerSocket(0)) {
            for (int i = 0; i < HostSockets.MAX_CONNECTIONS; i++) {
                held.add(new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort()));
                Socket accepted = server.accept();
                assertTrue(accepted instanceof javax.net.ssl.SSLSocket, "a TLS endpoint hands RMI TLS sockets");
                held.add(accepted);
            }
            assertEquals(HostSockets.MAX_CONNECTIONS, counters.open.get());
            try (Socket extra = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort())) {
                held.add(server.accept());
                Socket oldest = held.get(0);
                oldest.setSoTimeout(10_000);
                assertEquals(-1, oldest.getInputStream().read(), "the oldest connection was closed before any handshake");
                assertEquals(1, connections.evicted());
                assertEquals(HostSockets.MAX_CONNECTIONS, counters.open.get());
            }
        } finally {
            for (Socket s : held) {
                s.close();
            }
        }
    }

    /** An accepted connection that sends nothing is closed after the first-byte deadline; RMI is not told its address (the registry then refuses changes). */
    @Test
    void aConnectionThatSendsNothingIsClosedAfterTheFirstByteDeadline() throws Exception {
        HostSockets.Counters counters = new HostSockets.Counters();
        HostConnections connections = new HostConnections("deadline", 0);
        try (ServerSocket server = new HostSockets.Server(InetAddress.getLoopbackAddress(), null, counters, connections, 0).createServerSocket(0);
             Socket silent = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort());
             Socket accepted = server.accept()) {
            assertTrue(accepted.getInetAddress().isAnyLocalAddress(), "RMI sees no client address: " + accepted.getInetAddress());
            accepted.setSoTimeout(120_000); // what RMI asks for: the first byte is awaited for 5 s only
            long start = System.nanoTime();
            assertThrows(java.net.SocketTimeoutException.class, () -> accepted.getInputStream().read());
            long waited = (System.nanoTime() - start) / 1_000_000;
            assertTrue(waited >= HostConnections.FIRST_BYTE.toMillis() - 100 && waited < 60_000, "closed after the deadline, not RMI's timeout: " + waited + " ms");
            silent.setSoTimeout(10_000);
            assertEquals(-1, silent.getInputStream().read(), "the host closed it");
            assertEquals(1, connections.silent());
            assertEquals(0, connections.open());
        }
    }

    /**
     * Calls as RMI writes them (8 KiB pieces through its buffered stream, then a flush), one
     * smaller and one larger than what a client connection collects before writing, arrive whole
     * and in order through an endpoint connection that reads ahead, and are counted once.
     */
    @Test
    void callsCollectedUntilTheFlushAndReadAheadArriveWholeInOrderAndCountedOnce() throws Exception {
        HostSockets.Counters counters = new HostSockets.Counters();
        HostSockets.Server factory = new HostSockets.Server(InetAddress.getLoopbackAddress(), null, counters);
        byte[] small = new byte[100_000];
        byte[] large = new byte[HostSockets.COALESCE_MAX_BYTES * 2 + 12_345];
        java.util.Random random = new java.util.Random(7);
        random.nextBytes(small);
        random.nextBytes(large);
        try (ServerSocket server = factory.createServerSocket(0)) {
            HostSockets.Client client = new HostSockets.Client("127.0.0.1", false, 5_000);
            try (Socket c = client.createSocket("ignored", server.getLocalPort()); Socket accepted = server.accept()) {
                java.util.concurrent.CompletableFuture<byte[]> received = java.util.concurrent.CompletableFuture.supplyAsync(() -> {
                    try {
                        InputStream in = new BufferedInputStream(accepted.getInputStream());
                        return in.readNBytes(small.length + large.length);
                    } catch (java.io.IOException e) {
                        throw new java.io.UncheckedIOException(e);
                    }
                });
                OutputStream out = new BufferedOutputStream(c.getOutputStream());
                out.write(small);
                out.flush();
                out.write(large);
                out.flush();
                byte[] got = received.get(30, java.util.concurrent.TimeUnit.SECONDS);
                assertEquals(small.length + large.length, got.length);
                assertTrue(java.util.Arrays.equals(got, 0, small.length, small, 0, small.length), "the smaller call arrives whole");
                assertTrue(java.util.Arrays.equals(got, small.length, got.length, large, 0, large.length), "the larger call arrives whole, after it");
                assertEquals(small.length + large.length, counters.in.sum(), "every byte read is counted once");
            }
        }
    }

    /**
     * Under a flight recording (JFR's socket events, on by default in its "default" and "profile"
     * settings) an accepted connection reads and writes: JDK 17's recorder asks the socket for
     * its client's address after every read and write slower than its threshold, and an address
     * of {@code null} killed RMI's connection thread, so a host being profiled dropped calls.
     */
    @Test
    void anAcceptedConnectionReadsAndWritesWhileAFlightRecordingRecordsSocketEvents() throws Exception {
        HostSockets.Counters counters = new HostSockets.Counters();
        try (jdk.jfr.Recording recording = new jdk.jfr.Recording();
             ServerSocket server = new HostSockets.Server(InetAddress.getLoopbackAddress(), null, counters).createServerSocket(0);
             Socket client = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort());
             Socket accepted = server.accept()) {
            recording.enable("jdk.SocketRead").withThreshold(java.time.Duration.ZERO);
            recording.enable("jdk.SocketWrite").withThreshold(java.time.Duration.ZERO);
            recording.start();
            client.getOutputStream().write(new byte[] {0x50, 1, 2});
            byte[] got = accepted.getInputStream().readNBytes(3);
            accepted.getOutputStream().write(new byte[] {0x51, 4});
            client.setSoTimeout(10_000);
            assertEquals(0x51, client.getInputStream().read());
            assertEquals(4, client.getInputStream().read());
            assertEquals(3, got.length);
            recording.stop();
            java.nio.file.Path file = java.nio.file.Files.createTempFile("host-sockets", ".jfr");
            try {
                recording.dump(file);
                java.util.List<jdk.jfr.consumer.RecordedEvent> events = jdk.jfr.consumer.RecordingFile.readAllEvents(file);
                assertTrue(events.stream().anyMatch(e -> e.getEventType().getName().equals("jdk.SocketRead")
                        && e.getInt("port") == client.getLocalPort()), "the recorder saw the accepted connection's read: " + events);
            } finally {
                java.nio.file.Files.deleteIfExists(file);
            }
        }
    }
}
