package io.robomw.platform.nxt;

import io.robomw.api.ManualClock;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.Cycling;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformServices;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.platform.testkit.Framing;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.HexFormat;
import java.util.List;
import java.util.Map;
import java.util.Optional;

import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * The NXT driver's writes, byte for byte, against the telegrams of the review's walk of
 * {@code robot.move(0.5, 0.2)} (shared review §2): the two wheels' rotations pipelined with the
 * resets they need and the polls of the cycle, in one write; the brake that ends them; the idle
 * outputs a closing robot leaves.
 */
class NxtMotorDriverTest {

    /** A brick that answers every telegram with success; GETOUTPUTSTATE reports the output running, at rotation count 90. */
    private static byte[] answer(byte[] frame) {
        int opcode = frame[2 + NxtTelegram.OPCODE_OFFSET] & 0xFF;
        byte port = frame[2 + NxtTelegram.PAYLOAD_OFFSET];
        byte[] reply = new byte[opcode == NxtTelegram.GETOUTPUTSTATE ? NxtTelegram.GETOUTPUTSTATE_REPLY : NxtTelegram.STATUS_REPLY];
        reply[NxtTelegram.TYPE_OFFSET] = (byte) NxtTelegram.REPLY;
        reply[NxtTelegram.OPCODE_OFFSET] = (byte) opcode;
        if (opcode == NxtTelegram.GETOUTPUTSTATE) {
            int d = NxtTelegram.DATA_OFFSET;
            reply[d + NxtTelegram.OUT_PORT] = port;
            reply[d + NxtTelegram.OUT_MODE] = 0x07;
            reply[d + NxtTelegram.OUT_REGULATION] = 0x01;
            reply[d + NxtTelegram.OUT_RUN_STATE] = 0x20;
            LittleEndian.putU32(reply, d + NxtTelegram.OUT_ROTATION_COUNT, 90);
        }
        return NxtTelegram.withLengthPrefix(reply);
    }

    private final ScriptedLink link = new ScriptedLink().named("recording NXT")
            .framedBy(Framing.lengthPrefixed16LittleEndian()).answering(NxtMotorDriverTest::answer);

    /** @return the bytes written since the last call, in hex */
    private String takeWritten() {
        return HexFormat.of().withUpperCase().formatHex(link.takeWritten());
    }

    private final PlatformConfig config = new PlatformConfig("nxt-1", "nxt", new ConnectionSettings(Map.of("port", "/dev/rfcomm0"), "nxt.yaml"),
            List.of(new MotorChannel("B", MotorChannel.Role.LEFT_WHEEL, 0, Optional.empty()),
                    new MotorChannel("C", MotorChannel.Role.RIGHT_WHEEL, 0, Optional.empty())),
            List.of(), Duration.ofMillis(10), Duration.ZERO, new ManualClock(), PlatformServices.none(), Cycling.OWN_THREADS, FailurePolicy.logging());

    private static String hex(String spaced) {
        return spaced.replace(" ", "").replace("|", "").toUpperCase();
    }

    @Test
    void shouldWriteTheWalksTelegramsForAMoveItsBrakeAndItsClose() throws IOException {
        Communicator c = new Communicator(link);
        c.open();
        NxtMotorDriver driver = new NxtMotorDriver(config, new NxtBrick("nxt-1", new BrickChannel("nxt-1", c, Duration.ofMillis(200))));
        MotorPlatform motors = new MotorPlatform(config, driver);

        driver.send(List.of(new MotorState("B", 409.3, 1023.2, MotorState.StopMode.BRAKE),
                new MotorState("C", 409.3, 1023.2, MotorState.StopMode.BRAKE)), motors.feedback());
        assertEquals(hex("""
                03 00 00 21 01 | 04 00 00 0A 01 01 | 03 00 00 21 02 | 04 00 00 0A 02 01
                0C 00 00 04 01 2D 07 02 00 20 FF 03 00 00 | 0C 00 00 04 02 2D 07 02 00 20 FF 03 00 00
                03 00 00 06 01 | 03 00 00 06 02""").replace("\n", ""), takeWritten(), "the move: one write, 60 bytes");
        assertEquals(90, motors.motorDegrees("B"), "the polls in the same write report the encoders");

        driver.send(List.of(MotorState.stopped("B", MotorState.StopMode.BRAKE), MotorState.stopped("C", MotorState.StopMode.BRAKE)),
                motors.feedback());
        assertEquals(hex("0C 00 00 04 01 00 07 01 00 20 00 00 00 00 | 0C 00 00 04 02 00 07 01 00 20 00 00 00 00 | 03 00 00 06 01 | 03 00 00 06 02"),
                takeWritten(), "the brake, and the polls of motors that settle");

        driver.send(List.of(MotorState.stopped("B", MotorState.StopMode.COAST)), motors.feedback());
        assertEquals(hex("0C 00 00 04 01 00 00 00 00 00 00 00 00 00 | 03 00 00 06 01 | 03 00 00 06 02"), takeWritten(),
                "closing leaves the output idle");
    }
}
