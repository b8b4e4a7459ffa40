package io.robomw.platform.link;

import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/* Tests close links and pseudo-terminals inside try-with-resources on purpose: closing is what they test. */
@SuppressWarnings("try")
class TcpLinkTest {

    private static final String LOOPBACK = "127.0.0.1";
    private static final Duration SECOND = Duration.ofSeconds(1);

    private final ExecutorService reader = TestThreads.named("tcp-test-reader");

    @AfterEach
    void stopReader() throws InterruptedException {
        TestThreads.stop(reader);
    }

    private static TcpServerLink openServer() throws IOException {
        TcpServerLink server = new TcpServerLink(LOOPBACK, 0);
        server.open();
        return server;
    }

    private static TcpClientLink clientOf(TcpServerLink server) {
        return new TcpClientLink(LOOPBACK, server.localPort(), SECOND);
    }

    @Test
    void shouldPassAll256ByteValuesBothWaysOverTcp() throws IOException {
        byte[] all = TestBytes.allValues();
        try (TcpServerLink server = openServer();
             TcpClientLink client = clientOf(server)) {
            client.open();

            client.write(all, 0, all.length);
            assertArrayEquals(all, TestBytes.readFully(server::read, all.length, SECOND));

            server.write(all, 0, all.length);
            assertArrayEquals(all, TestBytes.readFully(client::read, all.length, SECOND));
        }
    }

    @Test
    void shouldReturnZeroWhenNoPeerConnectsWithinTimeout() throws IOException {
        try (TcpServerLink server = openServer()) {
            long start = System.nanoTime();
            int n = server.read(new byte[4], 0, 4, Duration.ofMillis(100));
            long elapsedMillis = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - start);

            assertEquals(0, n);
            assertTrue(elapsedMillis >= 100 && elapsedMillis < 1000, "waited " + elapsedMillis + " ms");
        }
    }

    @Test
    void shouldThrowLinkLostWhenClientDisconnectsThenAcceptNextClient() throws IOException {
        try (TcpServerLink server = openServer()) {
            try (TcpClientLink first = clientOf(server)) {
                first.open();
                first.write(new byte[] {1}, 0, 1);
                assertArrayEquals(new byte[] {1}, TestBytes.readFully(server::read, 1, SECOND));
            }
            LinkLostException lost = assertThrows(LinkLostException.class,
                    () -> server.read(new byte[1], 0, 1, SECOND));
            assertTrue(lost.getMessage().contains("closed the connection"), lost.getMessage());
            assertTrue(server.isOpen(), "the server keeps listening");

            try (TcpClientLink second = clientOf(server)) {
                second.open();
                second.write(new byte[] {2}, 0, 1);
                assertArrayEquals(new byte[] {2}, TestBytes.readFully(server::read, 1, SECOND));
                server.write(new byte[] {3}, 0, 1);
                assertArrayEquals(new byte[] {3}, TestBytes.readFully(second::read, 1, SECOND));
            }
        }
    }

    @Test
    void shouldThrowLinkLostOnClientWhenServerCloses() throws IOException {
        try (TcpServerLink server = openServer();
             TcpClientLink client = clientOf(server)) {
            client.open();
            client.write(new byte[] {1}, 0, 1);
            TestBytes.readFully(server::read, 1, SECOND);

            server.close();

            LinkLostException lost = assertThrows(LinkLostException.class,
                    () -> client.read(new byte[1], 0, 1, SECOND));
            assertEquals(client.describe(), lost.link());
        }
    }

    @Test
    void shouldRejectServerWriteWithoutPeer() throws IOException {
        try (TcpServerLink server = openServer()) {
            LinkLostException e = assertThrows(LinkLostException.class, () -> server.write(new byte[1], 0, 1));
            assertTrue(e.getMessage().contains("no peer is connected"), e.getMessage());
        }
    }

    @Test
    void shouldBindSamePortAgainWhenServerReopens() throws IOException {
        try (TcpServerLink server = openServer()) {
            int port = server.localPort();
            server.close();
            assertThrows(IllegalStateException.class, server::localPort);

            server.open();
            assertEquals(port, server.localPort());
        }
    }

    @Test
    void shouldFailToConnectWhenNothingListensNamingHostAndPort() throws IOException {
        int freePort;
        try (ServerSocket probe = new ServerSocket(0)) {
            freePort = probe.getLocalPort();
        }
        try (TcpClientLink client = new TcpClientLink(LOOPBACK, freePort, SECOND)) {
            IOException refused = assertThrows(IOException.class, client::open);
            assertTrue(refused.getMessage().contains("tcp 127.0.0.1:" + freePort), refused.getMessage());
            assertFalse(client.isOpen());
        }
    }

    @Test
    void shouldEndBlockedReadAsClosedNotLostWhenClosedLocally() throws Exception {
        try (TcpServerLink server = openServer();
             TcpClientLink client = clientOf(server)) {
            client.open();
            Future<Integer> blocked = reader.submit(() -> client.read(new byte[1], 0, 1, Duration.ofSeconds(5)));
            // The server never writes: the read is blocked until the client closes.
            client.close();

            ExecutionException failed = assertThrows(ExecutionException.class, () -> blocked.get(1, TimeUnit.SECONDS));
            IOException closed = assertInstanceOf(IOException.class, failed.getCause());
            assertFalse(closed instanceof LinkLostException, closed.toString());
        }
    }

    @Test
    void shouldDescribeClientAndServerByAddress() {
        assertEquals("tcp 127.0.0.1:65000", new TcpClientLink(LOOPBACK, 65000, SECOND).describe());
        assertEquals("tcp server 127.0.0.1:65001", new TcpServerLink(LOOPBACK, 65001).describe());
    }
}
