package io.robomw.sim.emulator.rcx;

import io.robomw.platform.link.SerialLink;
import io.robomw.platform.rcx.RcxPacket;
import io.robomw.platform.rcx.RcxPlatformProvider;
import io.robomw.sim.emulator.EmulatorStack;
import io.robomw.sim.emulator.LinkModel;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;

/**
 * The RCX emulator's wire behaviour as a client like NQC sees it through a real pseudo-terminal:
 * the tower's echo, then the brick's reply (protocols §3.3, §3.5), retransmissions and the toggle
 * bit, and garbled packets.
 */
class RcxEmulatorTest {

    @TempDir
    Path dir;

    private EmulatorStack<RcxEmulator> stack;
    private SerialLink tower;

    @BeforeEach
    void start() throws IOException {
        stack = new EmulatorStack<>(dir, RcxFullStackTest.ROBOT, "rcx-1", RcxEmulator::bind);
        stack.world(3, 1.0);
        RcxEmulator rcx = stack.newEmulator();
        rcx.linkModel(LinkModel.NONE);
        String pty = rcx.startOnPseudoTerminal();
        stack.sim().startRealTime(1);
        tower = new SerialLink(pty, RcxPlatformProvider.TOWER);
        tower.open();
    }

    @AfterEach
    void stop() {
        tower.close();
        stack.close();
    }

    private static byte[] hex(String s) {
        return HexFormat.of().parseHex(s.replace(" ", ""));
    }

    /** Sends a packet; returns everything that comes back (echo and reply) until the line is quiet. */
    private byte[] exchange(byte[] packet, int expected) throws IOException {
        tower.write(packet, 0, packet.length);
        byte[] in = new byte[expected];
        int got = 0;
        while (got < expected) {
            int n = tower.read(in, got, expected - got, Duration.ofSeconds(2));
            if (n == 0) {
                break;
            }
            got += n;
        }
        return java.util.Arrays.copyOf(in, got);
    }

    @Test
    void shouldEchoAPacketAndThenAnswerItAsTheDocumentedTrace() throws IOException {
        byte[] alive = hex("55 ff 00 10 ef 10 ef");
        assertArrayEquals(hex("55 ff 00 10 ef 10 ef 55 ff 00 ef 10 ef 10"), exchange(alive, 14));
        byte[] toggled = hex("55 ff 00 18 e7 18 e7");
        assertArrayEquals(hex("55 ff 00 18 e7 18 e7 55 ff 00 e7 18 e7 18"), exchange(toggled, 14), "the toggled alive, answered with its complement");
        byte[] battery = hex("55 FF 00 30 CF 30 CF");
        assertArrayEquals(hex("55 FF 00 30 CF 30 CF 55 FF 00 CF 30 54 AB 24 DB 47 B8"), exchange(battery, 18), "9300 mV");
    }

    @Test
    void shouldAnswerARetransmissionWithoutRunningItAgain() throws IOException {
        byte[] flip = RcxPacket.encode(RcxPacket.SET_MOTOR_DIRECTION, RcxPacket.setMotorDirection(RcxPacket.MOTOR_A, RcxPacket.FLIP));
        exchange(flip, 2 * flip.length - 2);
        exchange(flip, 2 * flip.length - 2);
        assertEquals(0x08 | 7 | 0x00, motorState(0) & 0x0F, "flipped once: the repeat was a retransmission (reverse, power 7)");

        byte[] flipAgain = RcxPacket.encode(RcxPacket.SET_MOTOR_DIRECTION | RcxPacket.TOGGLE, RcxPacket.setMotorDirection(RcxPacket.MOTOR_A, RcxPacket.FLIP));
        exchange(flipAgain, 2 * flipAgain.length - 2);
        assertEquals(7, motorState(0) & 0x0F, "the same command with the toggle bit runs again: forward");
    }

    @Test
    void shouldEchoButNotAnswerAGarbledPacket() throws IOException {
        byte[] garbled = hex("55 FF 00 12 ED 0C F3 00 FE 1E E1");
        assertArrayEquals(garbled, exchange(garbled, garbled.length + 11), "only the echo: the brick ignores what it cannot read");
        byte[] fine = hex("55 FF 00 30 CF 30 CF");
        assertEquals(18, exchange(fine, 18).length, "and answers the next packet");
    }

    @Test
    void shouldReportMotorStateAsTheFirmwareEncodesIt() throws IOException {
        exchange(RcxPacket.encode(RcxPacket.SET_MOTOR_POWER, RcxPacket.setMotorPower(RcxPacket.MOTOR_C, 3)), 26);
        exchange(RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF, RcxPacket.setMotorOnOff(RcxPacket.MOTOR_C, RcxPacket.ON)), 16);
        assertEquals(0x80 | 3, motorState(2), "on, forward, power 3");
        exchange(RcxPacket.encode(RcxPacket.SET_MOTOR_ON_OFF | RcxPacket.TOGGLE, RcxPacket.setMotorOnOff(RcxPacket.MOTOR_C, RcxPacket.OFF)), 16);
        assertEquals(0x40 | 3, motorState(2), "off (braking)");
    }

    private int motorState(int motor) throws IOException {
        byte[] request = RcxPacket.encode(RcxPacket.GET_VALUE | (motor % 2 == 0 ? 0 : RcxPacket.TOGGLE),
                RcxPacket.getValue(RcxPacket.SOURCE_MOTOR_STATE, motor));
        byte[] back = exchange(request, request.length + 11);
        byte[] reply = java.util.Arrays.copyOfRange(back, request.length, back.length);
        return RcxPacket.decode(reply).s16();
    }
}
