package io.robomw.platform.link;

import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static io.robomw.platform.link.SerialSettings.Parity.NONE;
import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/* Tests close links and pseudo-terminals inside try-with-resources on purpose: closing is what they test. */
@SuppressWarnings("try")
class PseudoTerminalTest {

    private static final Duration SECOND = Duration.ofSeconds(1);
    private static final SerialSettings SETTINGS = SerialSettings.of(9600, 8, NONE, 1);

    private final ExecutorService reader = TestThreads.named("pty-test-reader");

    @AfterEach
    void stopReader() throws InterruptedException {
        TestThreads.stop(reader);
    }

    @Test
    void shouldCreateSlaveDeviceThatExists() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open()) {
            assertTrue(pty.devicePath().startsWith("/dev/"), pty.devicePath());
            assertTrue(Files.exists(Path.of(pty.devicePath())), pty.devicePath());
        }
    }

    @Test
    void shouldPassAll256ByteValuesBothWaysOverPseudoTerminal() throws IOException {
        byte[] all = TestBytes.allValues();
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            link.open();

            link.write(all, 0, all.length);
            assertArrayEquals(all, TestBytes.readFully(pty::read, all.length, SECOND));

            pty.masterOutput().write(all);
            assertArrayEquals(all, TestBytes.readFully(link::read, all.length, SECOND));
        }
    }

    @Test
    void shouldPassAll256ByteValuesBothWaysWithItsOwnRawSettings() throws IOException {
        byte[] all = TestBytes.allValues();
        try (PseudoTerminal pty = PseudoTerminal.open();
             RawSlave slave = RawSlave.open(pty.devicePath())) {
            slave.write(all);
            assertArrayEquals(all, TestBytes.readFully(pty::read, all.length, SECOND));

            pty.masterOutput().write(all);
            assertArrayEquals(all, TestBytes.readFully(slave::read, all.length, SECOND));
        }
    }

    @Test
    void shouldReturnZeroWhenMasterReadTimesOut() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open()) {
            long start = System.nanoTime();
            int n = pty.read(new byte[8], 0, 8, Duration.ofMillis(150));
            long elapsedMillis = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - start);

            assertEquals(0, n);
            assertTrue(elapsedMillis >= 150 && elapsedMillis < 1000, "waited " + elapsedMillis + " ms");
        }
    }

    @Test
    void shouldSurviveDriverClosingAndReopeningSlave() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            for (int round = 1; round <= 3; round++) {
                link.open();
                byte[] request = {0x0C, 0x00, (byte) round};
                link.write(request, 0, request.length);
                assertArrayEquals(request, TestBytes.readFully(pty::read, request.length, SECOND));
                byte[] reply = {0x02, (byte) round, 0x0A, 0x0D};
                pty.masterOutput().write(reply);
                assertArrayEquals(reply, TestBytes.readFully(link::read, reply.length, SECOND));
                link.close();

                assertEquals(0, pty.read(new byte[1], 0, 1, Duration.ofMillis(20)),
                        "the master reads nothing, and no EIO, while no driver has the slave open");
            }
        }
    }

    @Test
    void shouldEndBlockedMasterInputWhenClosed() throws Exception {
        PseudoTerminal pty = PseudoTerminal.open();
        try {
            Future<Integer> blocked = reader.submit(() -> pty.masterInput().read());
            pty.close();
            assertEquals(-1, blocked.get(1, TimeUnit.SECONDS));
        } finally {
            pty.close();
        }
    }

    @Test
    void shouldRejectReadAndWriteAfterClose() throws IOException {
        PseudoTerminal pty = PseudoTerminal.open();
        pty.close();

        IOException read = assertThrows(IOException.class, () -> pty.read(new byte[1], 0, 1, SECOND));
        assertTrue(read.getMessage().contains(pty.devicePath()), read.getMessage());
        assertThrows(IOException.class, () -> pty.masterOutput().write(1));
    }
}
