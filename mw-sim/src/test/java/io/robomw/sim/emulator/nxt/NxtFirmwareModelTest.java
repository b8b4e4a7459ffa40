package io.robomw.sim.emulator.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.nxt.NxtStatus;
import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.EmulatorStack;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Arrays;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The emulator's firmware, telegram by telegram, on a simulated world advanced step by step (no
 * link, no driver): tacho limits as {@code d_output.c} counts them, UPDATE_RESET_COUNT, the
 * synchronised pair's block counts, and the ultrasonic sensor's identity registers. The telegrams
 * are written out as the protocol notes give them (§1.3, §1.6).
 */
class NxtFirmwareModelTest {

    private static final int B = 1;
    private static final int C = 2;
    /** power 50, MOTORON | BRAKE | REGULATED, speed regulation, turn 0, RUNNING. */
    private static final int ON_BRAKE_REGULATED = 0x07;
    /**
     * Degrees a motor at power 50 (450 °/s) coasts past its limit: the firmware's idle control
     * lowers its power by 1 a millisecond, so it runs on for 50 ms at half speed on average.
     */
    private static final int COAST = 11;

    @TempDir
    Path dir;

    private EmulatorStack<NxtEmulator> stack;
    private Simulation sim;
    private NxtEmulator nxt;

    @BeforeEach
    void world() throws Exception {
        stack = new EmulatorStack<>(dir, NxtEmulatorTest.ROBOT, "nxt-1", NxtEmulator::bind);
        sim = stack.world(3, 1.0);
        nxt = stack.newEmulator();
        sim.runFor(Duration.ofMillis(20));
    }

    @AfterEach
    void close() {
        stack.close();
    }

    private static byte[] setOutputState(int port, int power, int regulation, long limit) {
        byte[] t = {(byte) 0x80, 0x04, (byte) port, (byte) power, ON_BRAKE_REGULATED, (byte) regulation, 0, 0x20, 0, 0, 0, 0};
        LittleEndian.putU32(t, 8, limit);
        return t;
    }

    private byte[] getOutputState(int port) {
        return nxt.handle(new byte[]{0x00, 0x06, (byte) port});
    }

    private long tachoCount(int port) {
        return LittleEndian.s32(getOutputState(port), 13);
    }

    private long blockCount(int port) {
        return LittleEndian.s32(getOutputState(port), 17);
    }

    private long rotationCount(int port) {
        return LittleEndian.s32(getOutputState(port), 21);
    }

    private int runState(int port) {
        return getOutputState(port)[8] & 0xFF;
    }

    /** Runs the world until the output has been idle for a while (the coasting has died down). */
    private void runUntilIdle(int port) {
        assertTrue(sim.runUntil(() -> runState(port) == NxtTelegram.RUN_IDLE, Duration.ofSeconds(20)), "output " + port + " went idle");
        sim.runFor(Duration.ofMillis(300));
    }

    @Test
    void shouldAddASecondTachoLimitToTheTargetOfTheFirstNotToWhereTheMotorIs() {
        nxt.handle(setOutputState(B, 50, NxtTelegram.REGULATION_SPEED, 360));
        sim.runFor(Duration.ofMillis(300));
        long partWay = tachoCount(B);
        assertTrue(partWay > 60 && partWay < 300, "part way through the first rotation: " + partWay);

        nxt.handle(setOutputState(B, 50, NxtTelegram.REGULATION_SPEED, 360));
        runUntilIdle(B);

        assertEquals(720 + COAST, tachoCount(B), 8, "dOutputSetTachoLimit adds 360 to the target of 360: the motor ends near 720, not "
                + (partWay + 360));
    }

    @Test
    void shouldEndAReversedRotationAtOnceWhenTheRunningTargetIsAlreadyBehindTheMotor() {
        nxt.handle(setOutputState(B, 50, NxtTelegram.REGULATION_SPEED, 360));
        sim.runFor(Duration.ofMillis(300));
        long partWay = rotationCount(B);

        nxt.handle(setOutputState(B, -50, NxtTelegram.REGULATION_SPEED, 90));
        runUntilIdle(B);

        long moved = rotationCount(B) - partWay;
        assertTrue(moved >= 0 && moved < COAST + 8, "the target is 360 - 90 = 270, already passed going backwards: the motor goes idle at "
                + "once and coasts on, instead of turning back 90 degrees; it moved " + moved);
    }

    @Test
    void shouldCountATachoLimitFromWhereTheMotorIsAfterUpdateResetCount() {
        nxt.handle(setOutputState(B, 50, NxtTelegram.REGULATION_SPEED, 360));
        sim.runFor(Duration.ofMillis(300));
        long partWay = rotationCount(B);

        assertArrayEquals(new byte[]{0x02, 0x21, 0x00}, nxt.handle(new byte[]{0x00, 0x21, (byte) B}));
        assertEquals(0, tachoCount(B), 1, "UPDATE_RESET_COUNT zeroes the tacho count");
        nxt.handle(setOutputState(B, -50, NxtTelegram.REGULATION_SPEED, 90));
        runUntilIdle(B);

        assertEquals(partWay - 90 - COAST, rotationCount(B), 8, "back 90 degrees from where the reset found the motor, and its coasting");
    }

    @Test
    void shouldNotCountTheTachoCountFromEachSetOutputState() {
        nxt.handle(setOutputState(B, 50, NxtTelegram.REGULATION_SPEED, 180));
        runUntilIdle(B);
        long first = tachoCount(B);
        nxt.handle(setOutputState(B, 50, NxtTelegram.REGULATION_SPEED, 180));
        runUntilIdle(B);

        assertEquals(360 + COAST, tachoCount(B), 8, "the target and the tacho count go on across telegrams: " + first + " after the first");
    }

    @Test
    void shouldAnswerUnknownCommandToUpdateResetCountOnFirmwareBefore129() {
        NxtEmulator legacy = new NxtEmulator(io.robomw.sim.SimMotors.of(sim.world(), "nxt-1").orElseThrow(), sim.world().stepSeconds(), false);

        assertArrayEquals(new byte[]{0x02, 0x21, (byte) NxtStatus.UNKNOWN_COMMAND}, legacy.handle(new byte[]{0x00, 0x21, (byte) B}));
    }

    @Test
    void shouldKeepASynchronisedPairsBlockCountsTogetherSoAnUnresetDifferenceSteersIt() {
        nxt.handle(setOutputState(B, -30, NxtTelegram.REGULATION_SPEED, 90));
        nxt.handle(setOutputState(C, 30, NxtTelegram.REGULATION_SPEED, 90));
        runUntilIdle(B);
        runUntilIdle(C);
        long apart = blockCount(B) - blockCount(C);
        assertTrue(apart < -150, "a turn leaves the block counts apart: " + apart);
        long b0 = rotationCount(B);
        long c0 = rotationCount(C);

        nxt.handle(setOutputState(B, 40, NxtTelegram.REGULATION_SYNC, 360));
        nxt.handle(setOutputState(C, 40, NxtTelegram.REGULATION_SYNC, 360));
        runUntilIdle(B);

        long b = rotationCount(B) - b0;
        long c = rotationCount(C) - c0;
        assertTrue(b - c > 100, "without RESETMOTORPOSITION relative first, synchronisation works off the old difference: B turned "
                + b + ", C " + c);
    }

    @Test
    void shouldAnswerTheUltrasonicSensorsIdentityRegistersAsARealOneDoes() {
        nxt.handle(new byte[]{(byte) 0x80, 0x05, 0x03, 0x0B, 0x00});
        sim.runFor(Duration.ofMillis(20));

        assertEquals("V1.0", readRegisters(0x00, 8));
        assertEquals("LEGO", readRegisters(0x08, 8));
        assertEquals("Sonar", readRegisters(0x10, 8));
        assertEquals("10E-2m", readRegisters(0x14, 7));
    }

    @Test
    void shouldReadTheDistanceFromTheFirstMeasurementRegister() {
        nxt.handle(new byte[]{(byte) 0x80, 0x05, 0x03, 0x0B, 0x00});
        sim.runFor(Duration.ofMillis(20));

        byte[] data = readRegisterBytes(0x42, 1);

        double expectedCm = (3.0 - (1.0 + 0.10)) * 100;
        assertEquals(expectedCm, data[0] & 0xFF, 2.0);
    }

    /** LSWRITE port S4 tx [02 register] rx n, then (after an I²C cycle) LSGETSTATUS and LSREAD. */
    private byte[] readRegisterBytes(int register, int length) {
        assertArrayEquals(new byte[]{0x02, 0x0F, 0x00}, nxt.handle(new byte[]{0x00, 0x0F, 0x03, 0x02, (byte) length, 0x02, (byte) register}));
        assertEquals(NxtStatus.PENDING, nxt.handle(new byte[]{0x00, 0x0E, 0x03})[2] & 0xFF, "pending until the sensor answers");
        sim.runFor(Duration.ofMillis(20));
        byte[] status = nxt.handle(new byte[]{0x00, 0x0E, 0x03});
        assertEquals(NxtStatus.SUCCESS, status[2]);
        assertEquals(length, status[3]);
        byte[] read = nxt.handle(new byte[]{0x00, 0x10, 0x03});
        assertEquals(20, read.length, "LSREAD's reply always carries 16 data bytes");
        assertEquals(length, read[3]);
        return Arrays.copyOfRange(read, 4, 4 + length);
    }

    private String readRegisters(int register, int length) {
        byte[] data = readRegisterBytes(register, length);
        int end = 0;
        while (end < data.length && data[end] != 0) {
            end++;
        }
        return new String(data, 0, end, StandardCharsets.US_ASCII);
    }
}
