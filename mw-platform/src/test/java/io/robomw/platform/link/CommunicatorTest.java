package io.robomw.platform.link;

import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.io.OutputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static io.robomw.platform.link.SerialSettings.Parity.NONE;
import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/* Tests close links and pseudo-terminals inside try-with-resources on purpose: closing is what they test. */
@SuppressWarnings("try")
class CommunicatorTest {

    private static final Duration SECOND = Duration.ofSeconds(1);
    private static final Duration TWO_SECONDS = Duration.ofSeconds(2);
    private static final SerialSettings SETTINGS = SerialSettings.of(9600, 8, NONE, 1);

    private final ExecutorService receiver = TestThreads.named("communicator-test-receiver");

    @TempDir
    Path tempDir;

    @AfterEach
    void stopReceiver() throws InterruptedException {
        TestThreads.stop(receiver);
    }

    /** Counts events and lets the test wait for the first of each. */

    private static long millisSince(long startNanos) {
        return TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - startNanos);
    }

    @Test
    void shouldThrowLinkTimeoutAfterReceiveTimeoutOverPseudoTerminal() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(pty.devicePath(), SETTINGS))) {
            communicator.open();
            long start = System.nanoTime();
            LinkTimeoutException timeout = assertThrows(LinkTimeoutException.class,
                    () -> communicator.receive(Duration.ofMillis(200)));
            long elapsed = millisSince(start);

            assertTrue(elapsed >= 200 && elapsed < 2000, "waited " + elapsed + " ms");
            assertEquals("serial " + pty.devicePath() + ": no bytes arrived within the timeout of 200 ms",
                    timeout.getMessage());
            assertTrue(communicator.isOpen(), "a timeout does not lose the link");
        }
    }

    @Test
    void shouldThrowLinkTimeoutAfterReceiveTimeoutOverTcp() throws IOException {
        try (TcpServerLink server = new TcpServerLink("127.0.0.1", 0)) {
            server.open();
            try (Communicator communicator = new Communicator(new TcpClientLink("127.0.0.1", server.localPort(), SECOND))) {
                communicator.open();
                long start = System.nanoTime();
                assertThrows(LinkTimeoutException.class, () -> communicator.receive(Duration.ofMillis(200)));
                long elapsed = millisSince(start);

                assertTrue(elapsed >= 200 && elapsed < 2000, "waited " + elapsed + " ms");
            }
        }
    }

    @Test
    void shouldAssembleFrameDeliveredInThreeSeparateReads() throws IOException {
        ScriptedLink link = new ScriptedLink()
                .deliver(TestBytes.hex("0C 00"))
                .deliver(TestBytes.hex("00 04 05"))
                .deliver(TestBytes.hex("06 07"));
        try (Communicator communicator = new Communicator(link)) {
            communicator.open();
            assertArrayEquals(TestBytes.hex("0C 00 00 04 05 06 07"), communicator.receiveExactly(7, SECOND));
            assertEquals(3, link.reads());
        }
    }

    @Test
    void shouldAssembleFrameWrittenInThreePiecesOverPseudoTerminal() throws Exception {
        byte[] frame = TestBytes.hex("0A 00 80 09 00 0D 0A 03 11 13 FF 00");
        try (PseudoTerminal pty = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(pty.devicePath(), SETTINGS))) {
            communicator.open();
            Future<byte[]> received = receiver.submit(() -> communicator.receiveExactly(frame.length, TWO_SECONDS));

            OutputStream master = pty.masterOutput();
            master.write(frame, 0, 2);
            master.write(frame, 2, 5);
            master.write(frame, 7, 5);

            assertArrayEquals(frame, received.get(2, TimeUnit.SECONDS));
        }
    }

    @Test
    void shouldLeaveBytesBeyondRequestedLengthForNextReceive() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(pty.devicePath(), SETTINGS))) {
            communicator.open();
            pty.masterOutput().write(TestBytes.hex("04 00 01 02 02 00"));

            assertArrayEquals(TestBytes.hex("04 00 01 02"), communicator.receiveExactly(4, SECOND));
            assertArrayEquals(TestBytes.hex("02 00"), communicator.receiveExactly(2, SECOND));
        }
    }

    @Test
    void shouldSayHowManyBytesArrivedWhenReceiveExactlyTimesOut() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(pty.devicePath(), SETTINGS))) {
            communicator.open();
            pty.masterOutput().write(TestBytes.hex("05 00 01"));

            LinkTimeoutException timeout = assertThrows(LinkTimeoutException.class,
                    () -> communicator.receiveExactly(7, Duration.ofMillis(300)));
            assertTrue(timeout.getMessage().contains("received 3 of 7 bytes within the timeout of 300 ms"),
                    timeout.getMessage());
            assertEquals(Duration.ofMillis(300), timeout.timeout());
        }
    }

    @Test
    void shouldFailEveryTransferWithLinkLostOnceThePseudoTerminalClosesDuringReceive() throws Exception {
        Path logFile = tempDir.resolve("lost.log");
        try (PseudoTerminal pty = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(pty.devicePath(), SETTINGS), WireLog.open(logFile))) {
            communicator.open();
            Future<byte[]> blocked = receiver.submit(() -> communicator.receive(Duration.ofSeconds(5)));

            pty.close();

            ExecutionException failed = assertThrows(ExecutionException.class, () -> blocked.get(1, TimeUnit.SECONDS));
            LinkLostException lost = assertInstanceOf(LinkLostException.class, failed.getCause());
            assertEquals("serial " + pty.devicePath(), lost.link());

            assertThrows(LinkLostException.class, () -> communicator.receive(SECOND));
            assertThrows(LinkLostException.class, () -> communicator.send(new byte[] {1}));
        }
        assertTrue(Files.readAllLines(logFile).stream().anyMatch(line -> line.contains("link lost")), "the wire log notes the loss");
    }

    @Test
    void shouldReopenOnNewPseudoTerminalAfterDrop() throws Exception {
        Path port = tempDir.resolve("brick0");
        try (PseudoTerminal first = PseudoTerminal.open();
             PseudoTerminal second = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(port.toString(), SETTINGS))) {
            Files.createSymbolicLink(port, Path.of(first.devicePath()));
            communicator.open();
            communicator.send(new byte[] {1});
            assertArrayEquals(new byte[] {1}, TestBytes.readFully(first::read, 1, SECOND));

            first.close();
            assertThrows(LinkLostException.class, () -> communicator.receive(SECOND));

            // The device comes back under the same name, as a udev symlink does after a replug.
            Files.delete(port);
            Files.createSymbolicLink(port, Path.of(second.devicePath()));
            communicator.reopen();

            assertTrue(communicator.isOpen());
            communicator.send(new byte[] {2});
            assertArrayEquals(new byte[] {2}, TestBytes.readFully(second::read, 1, SECOND));
            second.masterOutput().write(3);
            assertArrayEquals(new byte[] {3}, communicator.receive(SECOND));
        }
    }

    @Test
    void shouldReopenTcpLinkAfterServerRestarts() throws Exception {
        try (TcpServerLink server = new TcpServerLink("127.0.0.1", 0)) {
            server.open();
            try (Communicator communicator = new Communicator(new TcpClientLink("127.0.0.1", server.localPort(), SECOND))) {
                communicator.open();
                communicator.send(new byte[] {1});
                assertArrayEquals(new byte[] {1}, TestBytes.readFully(server::read, 1, SECOND));

                server.close();
                assertThrows(LinkLostException.class, () -> communicator.receive(SECOND));

                server.open();
                communicator.reopen();

                communicator.send(new byte[] {2});
                assertArrayEquals(new byte[] {2}, TestBytes.readFully(server::read, 1, SECOND));
                server.write(new byte[] {3}, 0, 1);
                assertArrayEquals(new byte[] {3}, communicator.receive(SECOND));
            }
        }
    }

    @Test
    void shouldReceiveFromTheNextPeerOnAServerLinkAfterTheFirstHungUp() throws Exception {
        TcpServerLink server = new TcpServerLink("127.0.0.1", 0);
        try (Communicator communicator = new Communicator(server)) {
            communicator.open();

            try (TcpClientLink first = new TcpClientLink("127.0.0.1", server.localPort(), SECOND)) {
                first.open();
                first.write(new byte[] {1}, 0, 1);
                assertArrayEquals(new byte[] {1}, communicator.receive(SECOND));
            }
            assertThrows(LinkLostException.class, () -> communicator.receive(SECOND));

            try (TcpClientLink second = new TcpClientLink("127.0.0.1", server.localPort(), SECOND)) {
                second.open();
                second.write(new byte[] {2}, 0, 1);
                assertArrayEquals(new byte[] {2}, communicator.receive(SECOND));
            }
        }
    }

    @Test
    void shouldWriteTimestampedHexLinesToWireLog() throws IOException {
        Path logFile = tempDir.resolve("wire.log");
        try (PseudoTerminal pty = PseudoTerminal.open();
             Communicator communicator = new Communicator(new SerialLink(pty.devicePath(), SETTINGS),
                     WireLog.open(logFile))) {
            communicator.open();
            communicator.send(TestBytes.hex("0C 00 00 04"));
            TestBytes.readFully(pty::read, 4, SECOND);
            pty.masterOutput().write(TestBytes.hex("02 00 00 FF"));
            communicator.receiveExactly(4, SECOND);
        }

        List<String> lines = Files.readAllLines(logFile);
        String stamp = "\\d{4}-\\d{2}-\\d{2}T\\d{2}:\\d{2}:\\d{2}\\.\\d{6}Z";
        assertTrue(lines.get(0).matches(stamp + " > 0C 00 00 04"), lines.get(0));
        String received = String.join(" ", lines.subList(1, lines.size()).stream()
                .map(line -> line.substring(line.indexOf(" < ") + 3)).toList());
        assertTrue(lines.subList(1, lines.size()).stream().allMatch(line -> line.matches(stamp + " < [0-9A-F ]+")),
                lines.toString());
        assertEquals("02 00 00 FF", received);
    }

    @Test
    void shouldCloseLinkAndWireLogWithCommunicator() throws IOException {
        ScriptedLink link = new ScriptedLink();
        Path logFile = tempDir.resolve("closed.log");
        WireLog wireLog = WireLog.open(logFile);
        Communicator communicator = new Communicator(link, wireLog);
        communicator.open();
        communicator.send(new byte[] {0x0C});

        communicator.close();
        communicator.close();

        assertFalse(link.isOpen());
        assertFalse(communicator.isOpen());
        wireLog.sent(new byte[] {0x0D}, 0, 1);
        assertEquals(1, Files.readAllLines(logFile).size(), "nothing is written after close");
    }

    @Test
    void shouldKeepReceivingAfterALossWhenTheLinkMovesBytesAgain() throws IOException {
        ScriptedLink link = new ScriptedLink().deliverLoss().deliver(new byte[] {9});
        try (Communicator communicator = new Communicator(link)) {
            communicator.open();

            assertThrows(LinkLostException.class, () -> communicator.receive(SECOND));
            assertArrayEquals(new byte[] {9}, communicator.receive(SECOND));
            assertTrue(communicator.isOpen());
        }
    }
}
