package io.robomw.sim.emulator.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.ev3.Ev3Command;
import io.robomw.platform.ev3.Ev3Device;
import io.robomw.platform.ev3.Ev3Frame;
import io.robomw.platform.ev3.Ev3Reply;
import io.robomw.platform.motor.MotorState;
import io.robomw.sim.Simulation;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Arrays;
import java.util.HexFormat;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The EV3 emulator's firmware, telegram by telegram: the documented request bytes of the protocol
 * notes go in as the driver would send them, and the replies come out byte for byte, with the
 * motors and sensors of a robot in a simulated world that the test steps itself (no real time,
 * no pseudo-terminal: {@link Ev3Emulator#handle} is called directly).
 */
class Ev3EmulatorTest {

    /** An EV3 robot: wheels on B and C, an arm on A, and the sensor of each test on S4. */
    static final String ROBOT = """
            name: ev3-1
            platform: ev3
            connection: { port: /dev/unused }
            drive:
              wheel_diameter: 0.056
              track_width: 0.112
              max_speed: 0.30
              left:  { port: B }
              right: { port: C }
            body: { length: 0.20, width: 0.15, mass: 0.6, friction: 0.8 }
            sensors:
              - { name: bumper, type: touch, position: front, port: S1 }
              - { name: gyro, type: gyro, position: center, port: S2, conversion: { scale: -0.0174533 } }
              - { name: floor, type: light, position: bottom, port: S3, conversion: { scale: 0.01 } }
              %s
            actuators:
              - name: arm
                port: A
                actions:
                  up: { degrees: 90, speed: 180 }
            """;

    static final String SONAR = "- { name: sonar, type: sonar, position: front, port: S4, conversion: { scale: 0.01 } }";
    static final String INFRARED = "- { name: ir, type: infrared, position: front, port: S4, conversion: { scale: 0.007 } }";

    @TempDir
    Path dir;

    private Simulation sim;
    private Ev3Emulator emulator;

    @AfterEach
    void close() {
        if (emulator != null) {
            emulator.close();
            emulator = null;
        }
        if (sim != null) {
            sim.close();
            sim = null;
        }
    }

    /** A 3 m square arena with the robot at (x, 1.5); its front wall is at x = 3. */
    private void world(double x, double heading, String s4) throws IOException {
        world(3, x, heading, s4);
    }

    private void world(double width, double x, double heading, String s4) throws IOException {
        close();
        Files.writeString(dir.resolve("body.yaml"), ROBOT.formatted(s4));
        Files.writeString(dir.resolve("world.yaml"), """
                name: ev3-firmware
                arena: { width: %s, height: 3 }
                robots:
                  - { robot: body.yaml, name: ev3-1, x: %s, y: 1.5, heading: %s }
                """.formatted(width, x, heading));
        sim = Simulation.load(dir.resolve("world.yaml"), Set.of("ev3-1"));
        emulator = Ev3Emulator.bind(sim, "ev3-1");
        sim.runFor(Duration.ofMillis(100));
    }

    private static byte[] hex(String spaced) {
        return HexFormat.of().parseHex(spaced.replaceAll("[\\s|:]", ""));
    }

    private static String hex(byte[] bytes) {
        return bytes == null ? null : HexFormat.ofDelimiter(" ").withUpperCase().formatHex(bytes);
    }

    /** Hands a whole frame to the emulator as its I/O thread would, and returns the whole reply frame, or null. */
    private String send(byte[] frame) {
        assertEquals(frame.length - 2, Ev3Frame.length(frame), "test frame length field");
        byte[] reply = emulator.handle(Arrays.copyOfRange(frame, 2, frame.length));
        return reply == null ? null : hex(Ev3Frame.withLength(reply));
    }

    private String send(String frame) {
        return send(hex(frame));
    }

    private Ev3Reply request(Ev3Command command, int counter) {
        byte[] reply = emulator.handle(Arrays.copyOfRange(command.encode(counter), 2, command.encode(counter).length));
        return Ev3Reply.decode(Ev3Frame.withLength(reply));
    }

    private int count(int no) {
        return request(Ev3Command.withReply(4).outputGetCount(no, 0).build(), 1).data32(0);
    }

    private float readySi(int no, int type, int mode) {
        return request(Ev3Command.withReply(4).inputReadySi(no, type, mode, 0).build(), 1).dataF(0);
    }

    // ---- the documented examples, end to end ----

    @Test
    void shouldAnswerDocumentedTachoReplyAfterMotorATurned360Degrees() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputStepSpeed(0x01, 50, 0, 360, 0, MotorState.StopMode.BRAKE).build().encode(42)));
        sim.runFor(Duration.ofSeconds(2));
        assertEquals("07 00 2B 00 02 68 01 00 00", send("09 00 2B 00 00 04 00 B3 00 00 60"));
    }

    @Test
    void shouldRunDocumentedStepSpeedExampleOnMotorBFor720DegreesThenStop() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send("10 00 | 2A 00 | 80 | 00 00 | AE 00 02 81 32 00 82 D0 02 00 01"));
        sim.runFor(Duration.ofMillis(500));
        assertTrue(count(1) > 100 && count(1) < 720, "running: " + count(1));
        sim.runFor(Duration.ofSeconds(2));
        assertEquals(720, count(1), 1);
        int stopped = count(1);
        sim.runFor(Duration.ofSeconds(1));
        assertEquals(stopped, count(1), 0.5, "braked at the step");
        assertEquals(0, count(2), "motor C untouched");
    }

    @Test
    void shouldReportDocumentedTouchPressedReplyWhenDrivenAgainstTheWall() throws IOException {
        world(2.8, 0, SONAR);
        assertEquals("07 00 2A 00 02 00 00 00 00", send("0D 00 2A 00 00 04 00 99 1D 00 00 10 00 01 60"), "released");
        assertNull(send(Ev3Command.withoutReply().outputSpeed(0x06, 20).outputStart(0x06).build().encode(1)));
        sim.runFor(Duration.ofSeconds(2));
        assertEquals("07 00 2A 00 02 00 00 80 3F", send("0D 00 2A 00 00 04 00 99 1D 00 00 10 00 01 60"));
    }

    @Test
    void shouldAnswerCComHInputReadExampleWithReleasedTouch() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("04 00 34 12 02 00", send("0B 00 34 12 00 01 00 9A 00 00 00 00 60"));
    }

    @Test
    void shouldRunSpeedPlusStartExampleOnAAndIgnoreEmptyPortD() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send("0D 00 2C 00 80 00 00 A5 00 09 81 D8 A6 00 09"));
        sim.runFor(Duration.ofSeconds(1));
        assertEquals(-420, count(0), 11);
        assertEquals(0, count(3));
    }

    @Test
    void shouldStartAndStopMotorAWithCComHPowerExamples() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send("0C 00 01 00 80 00 00 A4 00 01 14 A6 00 01"));
        sim.runFor(Duration.ofSeconds(1));
        assertEquals(210, count(0), 11);
        assertNull(send("09 00 02 00 80 00 00 A3 00 01 00"));
        sim.runFor(Duration.ofMillis(100));
        int stopped = count(0);
        sim.runFor(Duration.ofSeconds(1));
        assertEquals(stopped, count(0));
    }

    @Test
    void shouldPlayToneExampleWithoutReply() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send("0E 00 30 00 80 00 00 94 01 02 82 B8 01 82 F4 01"));
        assertEquals(1, emulator.tonesPlayed());
    }

    @Test
    void shouldHoldEv3DcStepSpeedThenOutputReadyCommandUntilTheMotorArrives() throws Exception {
        world(1.5, 0, SONAR);
        byte[] code = hex("AE:00:02:05:0F:81:3C:0F:01:AA:00:02");
        byte[] frame = new byte[7 + code.length];
        LittleEndian.putU16(frame, 0, frame.length - 2);
        LittleEndian.putU16(frame, 2, 0x2A);
        System.arraycopy(code, 0, frame, 7, code.length);
        ExecutorService io = Executors.newSingleThreadExecutor(r -> new Thread(r, "test-ev3-io"));
        try {
            double start = sim.world().time();
            CompletableFuture<String> reply = CompletableFuture.supplyAsync(() -> send(frame), io);
            // Step until the reply comes, bounded in wall-clock time: stepping a fixed span of
            // simulated time could end before the I/O thread has even delivered the command.
            Await.until("the command was released when the motor arrived", Duration.ofSeconds(20), () -> {
                sim.runFor(Duration.ofMillis(20));
                return reply.isDone();
            });
            assertEquals("03 00 2A 00 02", reply.get());
            assertEquals(90, count(1), 1);
            assertTrue(sim.world().time() - start > 90 / 52.5, "a 90 degree step at speed 5 takes more than 1.7 s; took " + (sim.world().time() - start));
        } finally {
            io.shutdownNow();
        }
    }

    // ---- header and virtual-machine errors ----

    @Test
    void shouldAnswerBareErrorToCommandWithoutByteCodes() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("03 00 07 00 04", send("05 00 07 00 00 00 00"));
    }

    @Test
    void shouldAnswerBareErrorToMoreThan1021Globals() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("03 00 08 00 04", send("09 00 08 00 00 FE 03 B3 00 00 60"));
        String max = send("09 00 09 00 00 FD 03 B3 00 00 60");
        assertTrue(max.startsWith("00 04 09 00 02 00 00 00 00 00"), "1021 globals are the most, and are answered: " + max.substring(0, 30));
        assertEquals(1026, hex(max).length);
    }

    @Test
    void shouldNotAnswerMalformedCommandThatWantsNoReply() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send("05 00 07 00 80 00 00"));
    }

    @Test
    void shouldAnswerErrorWithGlobalsWrittenSoFarOnUnknownOpcode() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputStepSpeed(0x01, 50, 0, 360, 0, MotorState.StopMode.BRAKE).build().encode(1)));
        sim.runFor(Duration.ofSeconds(2));
        assertEquals("07 00 2B 00 04 68 01 00 00", send("0A 00 2B 00 00 04 00 B3 00 00 60 FF"));
        assertEquals(1, emulator.vmFailures());
    }

    @Test
    void shouldAnswerErrorToTachoCountOfOutputFour() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("07 00 01 00 04 00 00 00 00", send("09 00 01 00 00 04 00 B3 00 04 60"));
        assertEquals(1, emulator.vmFailures());
    }

    @Test
    void shouldAnswerErrorToReadingInputFive() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("07 00 02 00 04 00 00 00 00", send("0D 00 02 00 00 04 00 99 1D 00 05 00 3F 01 60"));
    }

    @Test
    void shouldAnswerErrorToLayerOneAsNoBrickIsDaisyChained() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("07 00 03 00 04 00 00 00 00", send("09 00 03 00 00 04 00 B3 01 00 60"));
    }

    @Test
    void shouldAnswerErrorToOutputBitBeyondD() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("03 00 04 00 04", send("09 00 04 00 00 00 00 A6 00 81 10"));
    }

    @Test
    void shouldAnswerErrorWhenAResultIsGivenAsAConstant() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("07 00 01 00 04 00 00 00 00", send("09 00 01 00 00 04 00 B3 00 00 00"));
    }

    @Test
    void shouldWriteResultsIntoLocalsAsWell() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("03 00 01 00 02", send("09 00 01 00 00 00 10 B3 00 00 40"), "4 locals, no globals");
    }

    @Test
    void shouldAnswerSystemCommandsWithSystemReplyError() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals("05 00 05 00 05 99 0A", send("06 00 05 00 01 99 00 00"));
    }

    // ---- motors ----

    @Test
    void shouldClearTachoCount() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputStepSpeed(0x01, 50, 0, 180, 0, MotorState.StopMode.BRAKE).build().encode(1)));
        sim.runFor(Duration.ofSeconds(1));
        assertEquals(180, count(0));
        assertEquals("03 00 05 00 02", send(Ev3Command.withReply(0).outputClrCount(0x01).build().encode(5)));
        assertEquals(0, count(0));
    }

    @Test
    void shouldReportBusyWhileSteppingThenIdle() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputStepSpeed(0x02, 20, 0, 90, 0, MotorState.StopMode.BRAKE).build().encode(1)));
        assertEquals("04 00 06 00 02 01", send("09 00 06 00 00 01 00 A9 00 02 60"));
        sim.runFor(Duration.ofSeconds(2));
        assertEquals("04 00 07 00 02 00", send("09 00 07 00 00 01 00 A9 00 02 60"));
    }

    @Test
    void shouldReadMotorAsSensorOnInput17() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputStepSpeed(0x02, 20, 0, 90, 0, MotorState.StopMode.BRAKE).build().encode(1)));
        sim.runFor(Duration.ofSeconds(2));
        assertEquals(90, readySi(17, Ev3Device.LARGE_MOTOR.type(), 0), 1);
    }

    // ---- sensors ----

    @Test
    void shouldReadUltrasonicDistanceInCentimetres() throws IOException {
        world(2.0, 0, SONAR);
        assertEquals(90.0, readySi(3, Ev3Device.ULTRASONIC.type(), 0), 0.5);
    }

    @Test
    void shouldReadUltrasonicRawInMillimetres() throws IOException {
        world(2.0, 0, SONAR);
        assertEquals(900, request(Ev3Command.withReply(4).inputReadyRaw(3, 0, -1, 0).build(), 1).data32(0), 5);
    }

    @Test
    void shouldReadUltrasonicPercentOf255Centimetres() throws IOException {
        world(2.0, 0, SONAR);
        assertEquals(35, request(Ev3Command.withReply(1).inputReadyPct(3, 0, -1, 0).build(), 1).data8(0), 1);
    }

    @Test
    void shouldReadUltrasonicInchesInMode1() throws IOException {
        world(2.0, 0, SONAR);
        assertEquals(35.4, readySi(3, Ev3Device.ULTRASONIC.type(), 1), 0.3);
    }

    @Test
    void shouldReportUltrasonic255BeyondRange() throws IOException {
        world(8, 0.5, 0, SONAR);
        assertEquals(255.0f, readySi(3, Ev3Device.ULTRASONIC.type(), 0));
    }

    @Test
    void shouldReadReflectedLightPercentOfTheFloor() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals(80.0f, readySi(2, Ev3Device.COLOR.type(), 0));
    }

    @Test
    void shouldReadGyroDegreesClockwisePositive() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputSpeed(0x02, 20).outputSpeed(0x04, -20).outputStart(0x06).build().encode(1)));
        sim.runFor(Duration.ofSeconds(1));
        double turned = Math.toDegrees(sim.world().robot("ev3-1").pose().heading());
        assertTrue(turned < -30, "turned clockwise: " + turned);
        assertNull(send(Ev3Command.withoutReply().outputStop(0x06, MotorState.StopMode.BRAKE).build().encode(2)));
        sim.runFor(Duration.ofMillis(100));
        turned = Math.toDegrees(sim.world().robot("ev3-1").pose().heading());
        assertEquals(-turned, readySi(1, Ev3Device.GYRO.type(), 0), 1.0);
        assertEquals(0, readySi(1, Ev3Device.GYRO.type(), 1), 1.0, "rate at rest");
    }

    @Test
    void shouldReadInfraredProximityPercentOfSeventyCentimetres() throws IOException {
        world(2.6, 0, INFRARED);
        assertEquals(0.30 / 0.70 * 100, readySi(3, Ev3Device.INFRARED.type(), 0), 1.0);
    }

    @Test
    void shouldReadInfraredProximityFullScaleBeyondSeventyCentimetres() throws IOException {
        world(1.0, 0, INFRARED);
        assertEquals(100.0f, readySi(3, Ev3Device.INFRARED.type(), 0));
    }

    @Test
    void shouldGiveNoValueForAnotherDeviceTypeThanThePluggedOne() throws IOException {
        world(1.5, 0, SONAR);
        assertTrue(Float.isNaN(readySi(0, Ev3Device.ULTRASONIC.type(), 0)));
        assertEquals(Ev3Reply.NAN_DATA32, request(Ev3Command.withReply(4).inputReadyRaw(0, Ev3Device.GYRO.type(), 0, 0).build(), 1).data32(0));
        assertEquals(Ev3Reply.NAN_DATA8, request(Ev3Command.withReply(1).inputReadyPct(0, Ev3Device.COLOR.type(), 0, 0).build(), 1).data8(0));
    }

    @Test
    void shouldGiveNoValueForAnEmptyPort() throws IOException {
        world(1.5, 0, "");
        assertTrue(Float.isNaN(readySi(3, 0, -1)));
    }

    @Test
    void shouldReportPluggedTypeAndMode() throws IOException {
        world(1.5, 0, SONAR);
        readySi(3, Ev3Device.ULTRASONIC.type(), 1);
        assertEquals("05 00 01 00 02 1E 01", send("0B 00 01 00 00 02 00 99 05 00 03 60 61"));
    }

    @Test
    void shouldReportBatteryVoltage() throws IOException {
        world(1.5, 0, SONAR);
        assertEquals(7.8f, request(Ev3Command.withReply(4).uiReadVbatt(0).build(), 1).dataF(0));
    }

    @Test
    void shouldStopItsMotorsWhenClosed() throws IOException {
        world(1.5, 0, SONAR);
        assertNull(send(Ev3Command.withoutReply().outputSpeed(0x06, 30).outputStart(0x06).build().encode(1)));
        sim.runFor(Duration.ofMillis(500));
        double moving = sim.world().robot("ev3-1").pose().x();
        assertTrue(moving > 1.55, "driving: " + moving);
        emulator.close();
        sim.runFor(Duration.ofMillis(200));
        double stopped = sim.world().robot("ev3-1").pose().x();
        sim.runFor(Duration.ofSeconds(1));
        assertEquals(stopped, sim.world().robot("ev3-1").pose().x(), 1e-3);
        assertFalse(Double.isNaN(stopped));
    }
}
