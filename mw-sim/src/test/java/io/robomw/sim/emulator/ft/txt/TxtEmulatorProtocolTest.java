package io.robomw.sim.emulator.ft.txt;

import io.robomw.platform.ft.txt.TxtProtocol;
import io.robomw.sim.Simulation;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.DataInputStream;
import java.io.IOException;
import java.net.InetAddress;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Set;
import java.util.function.Predicate;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The TXT emulator message by message over a raw socket on 127.0.0.1: every reply of the table
 * by id and size, framing by id, the counters, distance commands, input modes and link loss,
 * with the robot in a world running at four times real time. The real driver against the
 * emulator is {@link io.robomw.sim.emulator.EmulatorContractTest}.
 */
public class TxtEmulatorProtocolTest {

    /**
     * A two-wheeled TXT robot file whose {@code %s} is the inside of its {@code connection: { }}
     * block. Encoder resolution: the fischertechnik encoder motor gives 63 pulses per motor turn
     * (63⅓ really; the description takes 63), so on 56 mm wheels one pulse is π × 56 mm ÷ 63 =
     * 2.79 mm of wheel travel (5.7° of motor rotation), and a turn on the spot with a 112 mm track
     * is resolved to 2.86° of heading per pulse of one wheel. A driver waits up to 2 s for a reply
     * (a real TXT's default is 500 ms): the emulator's reply crosses three of its threads, which a
     * loaded host may each hold up, and a reply given up on is a lost link that fails the move.
     */
    public static final String ROBOT = """
            name: txt-1
            platform: ft-txt
            connection: { %s, reply_timeout_ms: 2000 }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              encoder_ticks_per_revolution: 63
              left:  { port: M1, counter: C1 }
              right: { port: M2, counter: C2 }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: bumper, type: touch, position: front, port: I1 }
              - { name: sonar, type: sonar, position: front, port: I2, conversion: { scale: 0.01 } }
            """;

    @TempDir
    Path dir;

    private Simulation sim;
    private TxtEmulator emulator;
    private Socket client;
    private DataInputStream in;

    @AfterEach
    void close() throws IOException {
        if (client != null) {
            client.close();
        }
        if (emulator != null) {
            emulator.close();
        }
        if (sim != null) {
            sim.close();
        }
    }

    /** The robot at (x, 1.5) facing the wall at x = 3, the emulator bound to it, not yet serving. */
    private void world(double x) throws IOException {
        Files.writeString(dir.resolve("body.yaml"), ROBOT.formatted("host: 127.0.0.1, port: 1"));
        Files.writeString(dir.resolve("world.yaml"), """
                name: txt-protocol
                arena: { width: 3, height: 3 }
                robots:
                  - { robot: body.yaml, name: txt-1, x: %s, y: 1.5, heading: 0 }
                """.formatted(x));
        sim = Simulation.load(dir.resolve("world.yaml"), Set.of("txt-1"));
        emulator = TxtEmulator.bind(sim, "txt-1");
    }

    private void start(double x) throws IOException {
        world(x);
        int port = emulator.startOnTcp("127.0.0.1", 0);
        sim.startRealTime(4);
        connect(port);
    }

    private void connect(int port) throws IOException {
        client = new Socket(InetAddress.getLoopbackAddress(), port);
        client.setSoTimeout(2000);
        client.setTcpNoDelay(true);
        in = new DataInputStream(client.getInputStream());
    }

    private byte[] request(byte[] message, int replyLength) throws IOException {
        client.getOutputStream().write(message);
        byte[] reply = new byte[replyLength];
        in.readFully(reply);
        return reply;
    }

    private TxtProtocol.ExchangeReply exchange(int[] pwm, int[] dist, int[] motorCmdId, int[] counterCmdId) throws IOException {
        byte[] reply = request(new TxtProtocol.Exchange(pwm, new int[4], dist, motorCmdId, counterCmdId, 0, 0, 0).encode(),
                TxtProtocol.EXCHANGE_REPLY_LENGTH);
        return TxtProtocol.ExchangeReply.decode(reply);
    }

    private TxtProtocol.ExchangeReply idle() throws IOException {
        return exchange(new int[8], new int[4], new int[4], new int[4]);
    }

    private void configure(int[] mode, int[] digital) throws IOException {
        byte[] config = new TxtProtocol.Config(1, 0, new int[]{1, 1, 1, 1}, mode, digital, new int[]{1, 1, 1, 1}, new int[16]).encode();
        assertArrayEquals(TxtProtocol.ack(TxtProtocol.UPDATE_CONFIG_REPLY), request(config, TxtProtocol.ACK_LENGTH));
    }

    /** Repeats an exchange (which also keeps the link alive) until its reply satisfies the condition. */
    private TxtProtocol.ExchangeReply exchangeUntil(int[] pwm, int[] dist, int[] motorCmdId, int[] counterCmdId,
                                                    Predicate<TxtProtocol.ExchangeReply> done, String what) throws IOException {
        TxtProtocol.ExchangeReply[] last = new TxtProtocol.ExchangeReply[1];
        Await.until(what, Duration.ofSeconds(10), () -> {
            try {
                last[0] = exchange(pwm, dist, motorCmdId, counterCmdId);
            } catch (IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
            return done.test(last[0]);
        }, () -> "; last reply " + last[0]);
        return last[0];
    }

    /**
     * Sends exchanges with every output off until counters C1 and C2 read the same in replies the
     * emulator made at least {@code seconds} of simulated time apart: the wheels stand still. Not
     * {@code seconds} from a time read before the first of them: on a loaded host the world may
     * run on at full PWM for that long before the emulator takes the stop (and the wheels turn for
     * a world step or two after it, as the world sets their speeds at its next step), so the
     * counters could still move after a reply that only looked late enough.
     *
     * @return the first reply of the stillness
     */
    private TxtProtocol.ExchangeReply untilStandingStill(double seconds) throws IOException {
        TxtProtocol.ExchangeReply[] still = new TxtProtocol.ExchangeReply[1];
        double[] stillAnsweredBy = {Double.NaN};
        TxtProtocol.ExchangeReply[] last = new TxtProtocol.ExchangeReply[1];
        Await.until("C1 and C2 unchanged for " + seconds + " simulated seconds: standing still", Duration.ofSeconds(10), () -> {
            double sent = sim.world().time(); // the emulator answers at this simulated time or later
            try {
                last[0] = idle();
            } catch (IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
            double answered = sim.world().time(); // ... and by this one
            int[] c = last[0].counterValue();
            if (still[0] == null || c[0] != still[0].counterValue()[0] || c[1] != still[0].counterValue()[1]) {
                still[0] = last[0];
                stillAnsweredBy[0] = answered;
                return false;
            }
            return sent >= stillAnsweredBy[0] + seconds;
        }, () -> "; last counters " + (last[0] == null ? "none" : java.util.Arrays.toString(last[0].counterValue()))
                + " at " + sim.world().time() + " s, unchanged since " + stillAnsweredBy[0] + " s");
        return still[0];
    }

    @Test
    void shouldAnswerEveryRequestOfTheTableWithItsReplyByIdAndSize() throws Exception {
        start(1.0);
        TxtProtocol.Status status = TxtProtocol.Status.decode(request(TxtProtocol.queryStatus(), TxtProtocol.QUERY_STATUS_REPLY_LENGTH));
        assertEquals(TxtEmulator.DEVICE_NAME, status.deviceName());
        assertEquals(TxtEmulator.FIRMWARE_VERSION, status.version());
        assertArrayEquals(TxtProtocol.ack(TxtProtocol.START_ONLINE_REPLY), request(TxtProtocol.startOnline(), TxtProtocol.ACK_LENGTH));
        assertTrue(emulator.isOnline());
        configure(new int[]{1, 1, 1, 1, 1, 1, 1, 1}, new int[]{1, 1, 1, 1, 1, 1, 1, 1});
        TxtProtocol.ExchangeReply r = idle();
        assertArrayEquals(new int[4], r.motorCmdId());
        assertArrayEquals(TxtProtocol.ack(TxtProtocol.STOP_ONLINE_REPLY), request(TxtProtocol.stopOnline(), TxtProtocol.ACK_LENGTH));
        assertFalse(emulator.isOnline());
        client.setSoTimeout(100);
        assertThrows(SocketTimeoutException.class, () -> in.read(), "nothing beyond the replies");
    }

    @Test
    void shouldDropAnUnknownIdAndAnswerTheNextMessage() throws Exception {
        start(1.0);
        client.getOutputStream().write(new byte[]{(byte) 0xA6, 0x40, 0x2A, (byte) 0x88, 0, 0, 0, 0});
        client.setSoTimeout(200);
        byte[][] reply = new byte[1][];
        Await.until("an answer after the unknown message", Duration.ofSeconds(5), () -> {
            try {
                reply[0] = request(TxtProtocol.queryStatus(), TxtProtocol.QUERY_STATUS_REPLY_LENGTH);
                return true;
            } catch (SocketTimeoutException e) {
                return false; // the emulator was still draining the bad input: our request went with it; ask again
            } catch (IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
        });
        assertEquals(TxtProtocol.QUERY_STATUS_REPLY, TxtProtocol.messageId(reply[0]));
        assertTrue(emulator.framesDropped() >= 1);
    }

    @Test
    void shouldStopADistanceCommandAfterItsPulsesAndThenEchoItsId() throws Exception {
        start(0.5);
        int[] pwm = {256, 0, 256, 0, 0, 0, 0, 0};
        int[] dist = {30, 30, 0, 0};
        int[] ids = {1, 1, 0, 0};
        TxtProtocol.ExchangeReply first = exchange(pwm, dist, ids, new int[4]);
        assertArrayEquals(new int[4], first.motorCmdId(), "not finished at once");
        TxtProtocol.ExchangeReply done = exchangeUntil(pwm, dist, ids, new int[4],
                r -> r.motorCmdId()[0] == 1 && r.motorCmdId()[1] == 1, "the distance command");
        int c1 = done.counterValue()[0];
        assertTrue(c1 >= 30 && c1 <= 31, "stopped at 30 pulses, counted " + c1);
        double stoppedAt = sim.world().time();
        exchangeUntil(pwm, dist, ids, new int[4], r -> sim.world().time() > stoppedAt + 0.05, "the stop to reach the physics");
        double x = sim.world().robot("txt-1").pose().x();
        double t0 = sim.world().time();
        exchangeUntil(pwm, dist, ids, new int[4], r -> sim.world().time() > t0 + 0.3, "0.3 s of simulated time");
        assertEquals(x, sim.world().robot("txt-1").pose().x(), 1e-9, "the motor stays stopped while the command is unchanged");
        assertEquals(0.5 + 30 * Math.PI * 0.056 / 63, x, 0.004, "30 pulses of 2.79 mm");
    }

    @Test
    void shouldRunWithoutLimitAndEchoAtOnceWhenTheDistanceIsZero() throws Exception {
        start(0.5);
        TxtProtocol.ExchangeReply r = exchange(new int[]{0, 512, 0, 512, 0, 0, 0, 0}, new int[4], new int[]{3, 3, 0, 0}, new int[4]);
        assertArrayEquals(new int[]{3, 3, 0, 0}, r.motorCmdId());
        exchangeUntil(new int[]{0, 512, 0, 512, 0, 0, 0, 0}, new int[4], new int[]{3, 3, 0, 0}, new int[4],
                reply -> sim.world().robot("txt-1").pose().x() < 0.45, "driving backwards");
        idle();
    }

    @Test
    void shouldResetACounterWhenItsCommandIdChanges() throws Exception {
        start(0.5);
        int[] pwm = {512, 0, 512, 0, 0, 0, 0, 0};
        exchangeUntil(pwm, new int[4], new int[4], new int[4], r -> r.counterValue()[0] >= 20 && r.counterValue()[1] >= 20, "counting");
        TxtProtocol.ExchangeReply stopped = untilStandingStill(0.2);
        TxtProtocol.ExchangeReply reset = exchange(new int[8], new int[4], new int[4], new int[]{1, 0, 0, 0});
        assertArrayEquals(new int[]{1, 0, 0, 0}, reset.counterCmdId(), "the reset is echoed");
        assertEquals(0, reset.counterValue()[0], "C1 restarted from 0");
        assertEquals(stopped.counterValue()[1], reset.counterValue()[1], "C2 was not reset");
        assertEquals(0, exchange(new int[8], new int[4], new int[4], new int[]{1, 0, 0, 0}).counterValue()[0],
                "an unchanged id resets nothing more");
    }

    @Test
    void shouldReportEachInputInTheModeConfiguredLast() throws Exception {
        start(2.0);
        idle();
        exchangeUntil(new int[8], new int[4], new int[4], new int[4], r -> sim.world().time() > 0.2, "the first sensor samples");
        configure(new int[]{1, 3, 1, 1, 1, 1, 1, 1}, new int[]{1, 0, 1, 1, 0, 1, 1, 1});
        TxtProtocol.ExchangeReply r = idle();
        assertEquals(0, r.input(0), "the bumper on I1 is released");
        assertEquals(90, r.input(1), 2, "the sonar on I2 reads the wall 0.90 m ahead in cm");
        assertEquals(15000, r.input(4), "nothing on I5: an open resistance");
        configure(new int[]{1, 1, 1, 1, 1, 1, 1, 1}, new int[]{1, 1, 1, 1, 1, 1, 1, 1});
        assertEquals(1, idle().input(1), "the very next reply is in the new mode: 0.90 m reads as a 1");
    }

    @Test
    void shouldStopTheMotorsWhenTheClientFallsSilent() throws Exception {
        start(0.5);
        exchange(new int[]{512, 0, 512, 0, 0, 0, 0, 0}, new int[4], new int[4], new int[4]);
        double[] lastX = {Double.NaN};
        double[] movedAt = {0};
        Await.until("the robot stood still for 0.2 simulated seconds: the motors stopped without messages", Duration.ofSeconds(10), () -> {
            double x = sim.world().robot("txt-1").pose().x();
            double t = sim.world().time();
            if (x != lastX[0]) {
                lastX[0] = x;
                movedAt[0] = t;
                return false;
            }
            return t > movedAt[0] + 0.2;
        });
        double last = lastX[0];
        assertTrue(last > 0.5, "it had been driving");
        assertTrue(last < 2.5, "it stopped by itself, not at the wall (x = 2.9): " + last);
    }

    @Test
    void shouldAcceptTheI2cConnectionOnTheCommandPortPlusTwo() throws Exception {
        world(1.0);
        int port = emulator.startOnTcpPair("127.0.0.1", 0);
        assertEquals(port + 2, emulator.i2cPort(), "port 0 picks a free pair P, P + 2");
        sim.startRealTime(4);
        try (Socket i2c = new Socket(InetAddress.getLoopbackAddress(), port + 2)) {
            connect(port);
            assertEquals(TxtProtocol.QUERY_STATUS_REPLY,
                    TxtProtocol.messageId(request(TxtProtocol.queryStatus(), TxtProtocol.QUERY_STATUS_REPLY_LENGTH)));
            assertTrue(i2c.isConnected());
        }
    }

    @Test
    void shouldRefuseAPortPairWhosePlusTwoDoesNotExist() throws Exception {
        world(1.0);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> emulator.startOnTcpPair("127.0.0.1", 65534));
        assertTrue(e.getMessage().contains("port + 2"), e.getMessage());
    }
}
