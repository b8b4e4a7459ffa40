package io.robomw.sim.emulator.nxt;

import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.sim.emulator.EmulatorStack;
import io.robomw.testkit.LogLines;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.DataInputStream;
import java.io.OutputStream;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A flood of bad telegrams must not flood the log (issue 15: the emulators logged one WARN line per
 * bad input): the NXT emulator, served over its TCP link, drops 500 telegrams too short to
 * hold an opcode, logs at most one line a second about them, and still answers a good telegram.
 */
class NxtEmulatorFloodTest {

    private static final int BAD = 500;

    @TempDir
    Path dir;

    @Test
    void fiveHundredBadTelegramsLogAFewLinesAndTheEmulatorStillAnswers() throws Exception {
        EmulatorStack<NxtEmulator> stack = new EmulatorStack<>(dir, NxtEmulatorTest.ROBOT, "nxt-1", NxtEmulator::bind);
        try (stack; LogLines log = new LogLines(); Socket peer = new Socket()) {
            stack.world(3, 1);
            NxtEmulator emulator = stack.newEmulator();
            int port = emulator.startOnTcp("127.0.0.1", 0);
            peer.connect(new InetSocketAddress("127.0.0.1", port), 5_000);
            peer.setSoTimeout(10_000);
            OutputStream out = peer.getOutputStream();

            long start = System.nanoTime();
            byte[] flood = new byte[3 * BAD];
            for (int i = 0; i < BAD; i++) {
                flood[3 * i] = 1; // a length prefix of 1: a telegram of one byte, no opcode
                flood[3 * i + 2] = (byte) i;
            }
            out.write(flood);
            out.flush();
            stack.awaitTrue(() -> emulator.framesDropped() == BAD, Duration.ofSeconds(30), BAD + " bad telegrams dropped");
            long elapsedSeconds = (System.nanoTime() - start) / 1_000_000_000L;

            List<String> drops = log.containing("dropped input");
            // One line at once, then at most one a second; one more for a line begun at a second's edge.
            assertTrue(!drops.isEmpty() && drops.size() <= elapsedSeconds + 2,
                    drops.size() + " lines for " + BAD + " bad telegrams in " + elapsedSeconds + " s, the first: " + drops.stream().limit(3).toList());

            byte[] battery = NxtTelegram.getBatteryLevel();
            out.write(new byte[] {(byte) battery.length, 0});
            out.write(battery);
            out.flush();
            DataInputStream in = new DataInputStream(peer.getInputStream());
            byte[] prefix = new byte[2];
            in.readFully(prefix);
            assertArrayEquals(new byte[] {NxtTelegram.GETBATTERYLEVEL_REPLY, 0}, prefix, "the good telegram is answered");
            byte[] reply = new byte[NxtTelegram.GETBATTERYLEVEL_REPLY];
            in.readFully(reply);
            assertEquals(NxtTelegram.REPLY, reply[0]);
            assertEquals(NxtTelegram.GETBATTERYLEVEL, reply[1]);
            assertEquals(0, reply[2], "status: success");
            assertEquals(BAD, emulator.framesDropped(), "only the bad telegrams were dropped");
        }
    }
}
