package io.robomw.platform.link;

import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.Arrays;
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
class SerialLinkTest {

    private static final Duration SECOND = Duration.ofSeconds(1);
    private static final SerialSettings SETTINGS = SerialSettings.of(9600, 8, NONE, 1);

    private final ExecutorService reader = TestThreads.named("serial-test-reader");

    @AfterEach
    void stopReader() throws InterruptedException {
        TestThreads.stop(reader);
    }

    @Test
    void shouldThrowLinkLostWithinOneSecondWhenPseudoTerminalCloses() throws Exception {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            link.open();
            Future<Integer> blocked = reader.submit(() -> link.read(new byte[16], 0, 16, Duration.ofSeconds(5)));

            long start = System.nanoTime();
            pty.close();
            ExecutionException failed = assertThrows(ExecutionException.class, () -> blocked.get(1, TimeUnit.SECONDS));
            long elapsedMillis = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - start);

            LinkLostException lost = assertInstanceOf(LinkLostException.class, failed.getCause());
            assertEquals(link.describe(), lost.link());
            assertTrue(lost.getMessage().startsWith("serial " + pty.devicePath()), lost.getMessage());
            assertTrue(elapsedMillis < 1000, "took " + elapsedMillis + " ms");
            assertTrue(link.isOpen(), "a lost link stays open until closed");
        }
    }

    @Test
    void shouldThrowLinkLostOnWriteAfterPseudoTerminalCloses() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            link.open();
            pty.close();

            byte[] frame = {1, 2, 3};
            assertThrows(LinkLostException.class, () -> link.write(frame, 0, frame.length));
        }
    }

    @Test
    void shouldReleasePortOnCloseSoItCanBeReopened() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            for (int round = 0; round < 3; round++) {
                link.open();
                assertTrue(link.isOpen());
                link.close();
                assertFalse(link.isOpen());
            }
            link.close();
        }
    }

    @Test
    void shouldRefuseSecondLinkToSameDeviceWhileFirstIsOpen() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink first = new SerialLink(pty.devicePath(), SETTINGS);
             SerialLink second = new SerialLink(pty.devicePath(), SETTINGS)) {
            first.open();

            IOException refused = assertThrows(IOException.class, second::open);
            assertTrue(refused.getMessage().contains(pty.devicePath()), refused.getMessage());

            first.close();
            second.open();
            assertTrue(second.isOpen());
        }
    }

    @Test
    void shouldFailToOpenMissingDeviceNamingItsPath() {
        try (SerialLink link = new SerialLink("/dev/robomw-no-such-port", SETTINGS)) {
            IOException missing = assertThrows(IOException.class, link::open);
            assertTrue(missing.getMessage().contains("/dev/robomw-no-such-port"), missing.getMessage());
            assertFalse(link.isOpen());
        }
    }

    @Test
    void shouldReturnZeroAfterReadTimeoutWithoutData() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            link.open();
            long start = System.nanoTime();
            int n = link.read(new byte[8], 0, 8, Duration.ofMillis(150));
            long elapsedMillis = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - start);

            assertEquals(0, n);
            assertTrue(elapsedMillis >= 150 && elapsedMillis < 1000, "waited " + elapsedMillis + " ms");
        }
    }

    @Test
    void shouldTakeOnlyBytesAlreadyThereWithZeroTimeout() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
             SerialLink link = new SerialLink(pty.devicePath(), SETTINGS)) {
            link.open();
            byte[] buf = new byte[8];
            long start = System.nanoTime();
            assertEquals(0, link.read(buf, 0, 8, Duration.ZERO));
            assertTrue(System.nanoTime() - start < TimeUnit.MILLISECONDS.toNanos(50), "a zero timeout does not wait");

            pty.masterOutput().write(new byte[] {7, 8, 9});
            assertEquals(1, link.read(buf, 0, 1, SECOND));
            assertEquals(2, link.read(buf, 1, 7, Duration.ZERO));
            assertArrayEquals(new byte[] {7, 8, 9}, Arrays.copyOf(buf, 3));
        }
    }

    @Test
    void shouldRejectTransfersWhenClosedWithoutCallingItLost() {
        try (SerialLink link = new SerialLink("/dev/robomw-never-opened", SETTINGS)) {
            IOException closed = assertThrows(IOException.class, () -> link.read(new byte[1], 0, 1, SECOND));
            assertFalse(closed instanceof LinkLostException, closed.toString());
            assertTrue(closed.getMessage().contains("is closed"), closed.getMessage());
        }
    }

    @Test
    void shouldDescribeItselfByDevicePath() {
        assertEquals("serial /dev/ttyUSB0", new SerialLink("/dev/ttyUSB0", SETTINGS).describe());
    }
}
