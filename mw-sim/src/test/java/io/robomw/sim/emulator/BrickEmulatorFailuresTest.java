package io.robomw.sim.emulator;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.PlatformServices;
import io.robomw.testkit.RecordingFailures;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.DataInputStream;
import java.io.IOException;
import java.io.InputStream;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentLinkedQueue;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * What a brick emulator's I/O thread does with what it catches, over a real TCP connection: a
 * telegram whose handling fails is dropped and reported, and the next is answered; a failure no
 * thread survives ends the emulator cleanly (its client sees the connection close) and is reported
 * as a death, to the policy its simulation was given.
 */
class BrickEmulatorFailuresTest {

    /** A brick that echoes each telegram, or throws what the test queued for it. */
    static final class ScriptedBrick extends BrickEmulator {
        final ConcurrentLinkedQueue<Throwable> failures = new ConcurrentLinkedQueue<>();

        ScriptedBrick(SimMotors robot) {
            super("scripted", robot, 64);
        }

        @Override
        protected byte[] handle(byte[] frame) {
            Throwable t = failures.poll();
            if (t instanceof Error e) {
                throw e;
            }
            if (t != null) {
                throw (RuntimeException) t;
            }
            return frame;
        }

        @Override
        protected void step(SimMotors robot) {
        }

        @Override
        protected void halt(SimMotors robot) {
        }

        static ScriptedBrick bind(Simulation sim, String robot) {
            return BrickEmulator.bind(sim, robot, ScriptedBrick::new);
        }
    }

    @TempDir
    Path dir;

    private final RecordingFailures failures = new RecordingFailures();
    private Simulation sim;
    private ScriptedBrick brick;
    private Socket client;

    private void start() throws IOException {
        Files.writeString(dir.resolve("brick.yaml"), """
                name: brick
                platform: nxt
                connection: { port: /dev/unused }
                drive: { wheel_diameter: 0.056, track_width: 0.112, max_speed: 0.3, left: { port: B }, right: { port: C } }
                """);
        Files.writeString(dir.resolve("world.yaml"), """
                name: bricks
                arena: { width: 2, height: 2 }
                robots:
                  - { robot: brick.yaml, name: b, x: 1, y: 1 }
                """);
        sim = Simulation.load(dir.resolve("world.yaml"), Set.of("b"), PlatformServices.none().with(FailurePolicy.class, failures));
        brick = ScriptedBrick.bind(sim, "b");
        int port = brick.startOnTcp("127.0.0.1", 0);
        client = new Socket("127.0.0.1", port);
        client.setSoTimeout(10_000);
    }

    @AfterEach
    void close() throws IOException {
        if (client != null) {
            client.close();
        }
        if (brick != null) {
            brick.close();
        }
        if (sim != null) {
            sim.close();
        }
    }

    /** Sends a length-prefixed telegram. */
    private void send(byte... telegram) throws IOException {
        byte[] out = new byte[telegram.length + 2];
        out[0] = (byte) telegram.length;
        System.arraycopy(telegram, 0, out, 2, telegram.length);
        client.getOutputStream().write(out);
        client.getOutputStream().flush();
    }

    private byte[] receive() throws IOException {
        DataInputStream in = new DataInputStream(client.getInputStream());
        int length = in.readUnsignedByte() | in.readUnsignedByte() << 8;
        byte[] reply = new byte[length];
        in.readFully(reply);
        return reply;
    }

    @Test
    void shouldDropAndReportATelegramWhoseHandlingFailsAndAnswerTheNext() throws Exception {
        start();
        AssertionError injected = new AssertionError("the firmware model's bug");
        brick.failures.add(injected);

        send((byte) 1, (byte) 2);
        send((byte) 3, (byte) 4);

        assertArrayEquals(new byte[]{3, 4}, receive(), "the telegram after the failed one is answered");
        assertEquals(1, brick.framesDropped());
        assertEquals(1, brick.framesServed());
        assertEquals(List.of(new RecordingFailures.Report("emulator-scripted-b: telegram 01 02", injected, false)), failures.reports());
    }

    @Test
    void shouldEndCleanlyAndCloseItsLinkWhenItsThreadDiesOfAnErrorNoThreadSurvives() throws Exception {
        start();
        OutOfMemoryError injected = new OutOfMemoryError("injected into the brick");
        brick.failures.add(injected);

        send((byte) 1);

        InputStream in = client.getInputStream();
        int read;
        try {
            read = in.read();
        } catch (SocketTimeoutException e) {
            throw new AssertionError("the client was left waiting: the dead emulator's link stayed open", e);
        } catch (IOException e) {
            read = -1; // reset: closed as well
        }
        assertEquals(-1, read, "the client sees the link close");
        Await.until("the death reported", Duration.ofSeconds(10), () -> !failures.deaths().isEmpty());
        assertEquals(List.of(new RecordingFailures.Report("emulator-scripted-b", injected, true)), failures.reports());
        Await.until("the I/O thread ended", Duration.ofSeconds(10),
                () -> Thread.getAllStackTraces().keySet().stream().noneMatch(t -> t.getName().equals("emulator-scripted-b") && t.isAlive()));
        assertFalse(brick.describe().isEmpty());
        assertTrue(brick.framesServed() == 0);
    }
}
