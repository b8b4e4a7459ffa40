package io.robomw.cli;

import io.robomw.platform.ft.txt.TxtProtocol;
import io.robomw.platform.mavlink.link.UdpMavlinkLink;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.MavAutopilot;
import io.robomw.platform.mavlink.wire.MavType;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.Payload;
import io.robomw.platform.link.SerialLink;
import io.robomw.platform.rcx.RcxPacket;
import io.robomw.platform.rcx.RcxPlatformProvider;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

import java.io.DataInputStream;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.io.Writer;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * {@code mw emulate} through picocli, as the launcher runs it, on its own thread; the test ends it
 * as Ctrl-C would end the process' wait (by interrupting it).
 */
class EmulateCommandTest {

    private static final Path TXT_ROBOT = Path.of("../examples/robots/ft-txt.yaml").toAbsolutePath().normalize();
    private static final Path HARBOUR = Path.of("../examples/worlds/harbour.yaml").toAbsolutePath().normalize();
    private static final Path RCX_ROBOT = Path.of("../examples/robots/rcx-two-wheeled.yaml").toAbsolutePath().normalize();

    @TempDir
    Path dir;

    private Thread command;
    private final BlockingQueue<String> lines = new LinkedBlockingQueue<>();

    @AfterEach
    void stop() throws InterruptedException {
        if (command != null) {
            command.interrupt();
            command.join(10_000);
            assertTrue(!command.isAlive(), "mw emulate ended when interrupted");
        }
    }

    /** Starts {@code mw emulate ...}; its standard output's lines arrive in {@link #lines}. */
    private void start(String... args) {
        Writer out = new Writer() {
            private final StringBuilder line = new StringBuilder();

            @Override
            public void write(char[] buf, int off, int len) {
                for (int i = off; i < off + len; i++) {
                    if (buf[i] == '\n') {
                        lines.add(line.toString());
                        line.setLength(0);
                    } else {
                        line.append(buf[i]);
                    }
                }
            }

            @Override
            public void flush() {
            }

            @Override
            public void close() {
            }
        };
        CommandLine cl = Mw.commandLine(); // as the launcher runs it: its converters (durations) and handlers
        cl.setOut(new PrintWriter(out, true));
        cl.setErr(new PrintWriter(new StringWriter(), true));
        command = new Thread(() -> cl.execute(args), "mw-emulate-under-test");
        command.start();
    }

    /** @return the robot file's name, copied beside the test's world: a world may name robot files in its own tree only (issue 37) */
    private String beside(Path robot) throws java.io.IOException {
        Files.copy(robot, dir.resolve(robot.getFileName()), java.nio.file.StandardCopyOption.REPLACE_EXISTING);
        return robot.getFileName().toString();
    }

    @Test
    void shouldServeTheTxtsCommandPortAndAcceptItsI2cChannelOnPortPlusTwo() throws Exception {
        Files.writeString(dir.resolve("world.yaml"), """
                name: txt-world
                arena: { width: 3, height: 3 }
                robots:
                  - { robot: %s, name: txt, x: 1.0, y: 1.5, heading: 0 }
                """.formatted(beside(TXT_ROBOT)));
        start("emulate", "ft-txt", "--world", dir.resolve("world.yaml").toString(), "--robot", "txt", "--tcp", "0");
        String where = lines.poll(30, TimeUnit.SECONDS);
        assertNotNull(where, "mw emulate printed where it serves");
        assertTrue(where.startsWith("tcp://127.0.0.1:"), where);
        int port = Integer.parseInt(where.substring("tcp://127.0.0.1:".length()));

        try (Socket commands = connect(port); Socket i2c = connect(port + 2)) {
            commands.getOutputStream().write(id(TxtProtocol.QUERY_STATUS));
            byte[] reply = new byte[TxtProtocol.QUERY_STATUS_REPLY_LENGTH];
            new DataInputStream(commands.getInputStream()).readFully(reply);
            assertEquals(TxtProtocol.QUERY_STATUS_REPLY, TxtProtocol.messageId(reply), "the command port answers queryStatus");
            assertTrue(i2c.isConnected(), "the I²C channel on port + 2 accepted the connection, as ftrobopy's startOnline needs");
        }
    }

    @Test
    void shouldServeAnRcxBehindItsEchoingTowerOnAPseudoTerminal() throws Exception {
        Files.writeString(dir.resolve("world.yaml"), """
                name: rcx-world
                arena: { width: 3, height: 3 }
                robots:
                  - { robot: %s, name: rcx, x: 1.0, y: 1.5, heading: 0 }
                """.formatted(beside(RCX_ROBOT)));
        start("emulate", "rcx", "--world", dir.resolve("world.yaml").toString(), "--robot", "rcx", "--latency", "0", "--baud", "0");
        String device = lines.poll(30, TimeUnit.SECONDS);
        assertNotNull(device, "mw emulate printed the device");
        assertTrue(device.startsWith("/dev/"), device);

        try (SerialLink tower = new SerialLink(device, RcxPlatformProvider.TOWER)) {
            tower.open();
            byte[] alive = RcxPacket.encode(RcxPacket.ALIVE);
            tower.write(alive, 0, alive.length);
            byte[] back = new byte[2 * alive.length];
            int got = 0;
            while (got < back.length) {
                int n = tower.read(back, got, back.length - got, Duration.ofSeconds(5));
                assertTrue(n > 0, "the echo and the reply came");
                got += n;
            }
            assertArrayEquals(alive, java.util.Arrays.copyOf(back, alive.length), "the tower's echo");
            assertEquals(RcxPacket.replyOpcode(RcxPacket.ALIVE), RcxPacket.decode(java.util.Arrays.copyOfRange(back, alive.length, back.length)).opcode());
        }
    }

    private static Socket connect(int port) throws IOException {
        Socket s = new Socket();
        s.connect(new InetSocketAddress("127.0.0.1", port), 5000);
        s.setSoTimeout(5000);
        return s;
    }

    private static byte[] id(long messageId) {
        return ByteBuffer.allocate(4).order(ByteOrder.LITTLE_ENDIAN).putInt((int) messageId).array();
    }

    @Test
    void latencyIsADurationAsEveryOtherTimeOption() throws Exception {
        Files.writeString(dir.resolve("world.yaml"), """
                name: rcx-world
                arena: { width: 3, height: 3 }
                robots:
                  - { robot: %s, name: rcx, x: 1.0, y: 1.5, heading: 0 }
                """.formatted(beside(RCX_ROBOT)));
        start("emulate", "rcx", "--world", dir.resolve("world.yaml").toString(), "--robot", "rcx", "--latency", "30ms", "--baud", "0");
        String device = lines.poll(30, TimeUnit.SECONDS);
        assertNotNull(device, "mw emulate started with --latency 30ms");
        assertTrue(device.startsWith("/dev/"), device);
    }

    @Test
    void aBareLatencyLongerThanAnyLinkIsRefusedAskingForAUnit() throws Exception {
        Files.writeString(dir.resolve("world.yaml"), """
                name: rcx-world
                arena: { width: 3, height: 3 }
                robots:
                  - { robot: %s, name: rcx, x: 1.0, y: 1.5, heading: 0 }
                """.formatted(beside(RCX_ROBOT)));
        CliRun run = CliRun.mw("emulate", "rcx", "--world", dir.resolve("world.yaml").toString(), "--robot", "rcx", "--latency", "40");
        assertEquals(2, run.status(), run.toString());
        assertTrue(run.err().contains("--latency 40s is longer than any link's (at most 10s); give a unit: --latency 40ms"), run.err());
    }

    @Test
    void theMavlinkEmulatorAnswersOnLoopbackAsTheWorldsBoat() throws Exception {
        start("emulate", "mavlink", "--world", HARBOUR.toString(), "--robot", "boat", "--udp", "0");
        String where = lines.poll(30, TimeUnit.SECONDS);
        assertNotNull(where, "mw emulate mavlink printed its address");
        assertTrue(where.startsWith("udp://127.0.0.1:"), "it listens on loopback only: " + where);
        int port = Integer.parseInt(where.substring("udp://127.0.0.1:".length()));
        BlockingQueue<Frame> heard = new LinkedBlockingQueue<>();
        try (UdpMavlinkLink gcs = UdpMavlinkLink.sendTo(new InetSocketAddress("127.0.0.1", port), System::nanoTime)) {
            gcs.send(new FrameEncoder(255, 190).encode(Payload.of(Messages.Heartbeat.MESSAGE).set(Messages.Heartbeat.TYPE, MavType.GCS.code())
                    .set(Messages.Heartbeat.AUTOPILOT, MavAutopilot.INVALID.code()).set(Messages.Heartbeat.MAVLINK_VERSION, 3)));
            long deadline = System.nanoTime() + Duration.ofSeconds(30).toNanos();
            Frame hb = null;
            while (hb == null && System.nanoTime() < deadline) {
                gcs.receive(Duration.ofMillis(500), (f, from) -> heard.add(f));
                for (Frame f = heard.poll(); f != null && hb == null; f = heard.poll()) {
                    hb = f.is(Messages.Heartbeat.MESSAGE) ? f : null;
                }
            }
            assertNotNull(hb, "the emulator's HEARTBEAT came back within 30 s");
            assertEquals(MavType.SURFACE_BOAT.code(), hb.payload().getLong(Messages.Heartbeat.TYPE), "a surface boat (11)");
            assertEquals(MavAutopilot.ARDUPILOTMEGA.code(), hb.payload().getLong(Messages.Heartbeat.AUTOPILOT), "the boat's file says ArduPilot");
        }
    }

    @Test
    void aSigningPassphraseAsAnOptionValueIsRefusedNamingTheFileOption() {
        CliRun run = CliRun.mw("emulate", "mavlink", "--world", HARBOUR.toString(), "--robot", "boat", "--signing-key", "harbour pilots");
        assertEquals(2, run.status(), run.toString());
        assertTrue(run.err().contains("--signing-key-file FILE") && run.err().contains("MW_MAVLINK_SIGNING_KEY"), run.err());
    }

    @Test
    void anUnreadableSigningKeyFileIsRefusedNamingIt() {
        Path missing = dir.resolve("no-such.key");
        CliRun run = CliRun.mw("emulate", "mavlink", "--world", HARBOUR.toString(), "--robot", "boat", "--udp", "0",
                "--signing-key-file", missing.toString());
        assertEquals(2, run.status(), run.toString());
        assertTrue(run.err().contains("no-such.key"), run.err());
    }
}
