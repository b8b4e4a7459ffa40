package io.robomw.platform.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.SensorType;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.PlatformServices;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.testkit.Answer;
import io.robomw.platform.testkit.ScriptedLink;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.ServiceLoader;
import java.util.concurrent.ExecutionException;
import java.util.function.Function;

import static io.robomw.platform.ev3.Ev3CodecTest.hex;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The EV3 driver's motor and sensor platforms: what they send for each motor state and sensor,
 * checked as bytes on a scripted link, and how they read the replies.
 */
class Ev3PlatformTest {

    private ScriptedLink link;

    /** @return a brick whose far end answers each frame written with what {@code responder} makes of it */
    private Ev3Brick brick(Function<byte[], Answer> responder) throws IOException {
        link = new ScriptedLink().named("ev3 link").answeringWith(responder);
        Communicator c = new Communicator(link);
        c.open();
        return new Ev3Brick("ev3-test", new BrickChannel("ev3-test", c, Duration.ofMillis(200)));
    }

    private static PlatformConfig config(List<String> motors) {
        return new PlatformConfig("ev3-test", "ev3", new ConnectionSettings(Map.of(), "test.yaml"),
                motors.stream().map(io.robomw.api.spi.MotorChannel::actuator).toList(), List.of(),
                Duration.ofMillis(10), Duration.ZERO, Clock.system(), PlatformServices.none(), io.robomw.api.spi.Cycling.OWN_THREADS, io.robomw.api.spi.FailurePolicy.logging());
    }

    private static Answer replyWithGlobals(byte[] frame, byte[] globals) {
        return Answer.of(Ev3BrickTest.okReply(frame, globals));
    }

    private static Answer emptyReply(byte[] frame) {
        return replyWithGlobals(frame, new byte[Ev3Frame.globalsOf(LittleEndian.u16(frame, Ev3Frame.VARS_FIELD_OFFSET))]);
    }

    @Test
    void shouldBeFoundByServiceLoaderAsEv3() {
        assertTrue(ServiceLoader.load(PlatformProvider.class).stream()
                .anyMatch(p -> p.get().platformName().equals("ev3") && p.type() == Ev3PlatformProvider.class));
    }

    @ParameterizedTest(name = "{0} deg/s -> {1} %")
    @CsvSource({"1050, 100", "2000, 100", "525, 50", "-315, -30", "307.9, 29", "3, 1", "-3, -1", "0, 0"})
    void shouldTurnDegreesPerSecondIntoRegulatedSpeedPercent(double degreesPerSecond, int percent) {
        assertEquals(percent, Ev3MotorDriver.speedPercent(degreesPerSecond));
    }

    @Test
    void shouldSendLimitedMovesAsStepSpeedInOneCommandSoBothWheelsStartTogether() {
        Ev3Command c = Ev3MotorDriver.commandFor(List.of(
                new MotorState("B", 307.0, 1023.4, MotorState.StopMode.BRAKE),
                new MotorState("C", -307.0, 1023.4, MotorState.StopMode.BRAKE)));
        assertEquals("AE 00 02 1D 00 82 FF 03 00 01 AE 00 04 23 00 82 FF 03 00 01", hex(c.code()));
        assertTrue(c.replyWanted());
        assertEquals(0, c.globals());
    }

    @Test
    void shouldSendContinuousRunAsSpeedThenStart() {
        Ev3Command c = Ev3MotorDriver.commandFor(List.of(new MotorState("A", -420, Double.POSITIVE_INFINITY, MotorState.StopMode.BRAKE)));
        assertEquals("A5 00 01 81 D8 A6 00 01", hex(c.code()));
    }

    @Test
    void shouldSendStopBrakingOrCoasting() {
        Ev3Command c = Ev3MotorDriver.commandFor(List.of(MotorState.stopped("D", MotorState.StopMode.BRAKE),
                MotorState.stopped("B", MotorState.StopMode.COAST)));
        assertEquals("A3 00 08 01 A3 00 02 00", hex(c.code()));
    }

    @Test
    void shouldRefuseMotorPortsTheEv3DoesNotHave() throws IOException {
        Ev3Brick brick = brick(Ev3PlatformTest::emptyReply);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new Ev3MotorDriver(config(List.of("B", "E")), brick));
        assertTrue(e.getMessage().contains("'E'"), e.getMessage());
    }

    @Test
    void shouldPollEveryEncoderInOneCommandAndReportDegrees() throws IOException {
        byte[] counts = new byte[8];
        LittleEndian.putU32(counts, 0, 360);
        LittleEndian.putU32(counts, 4, -90);
        Ev3Brick brick = brick(f -> replyWithGlobals(f, counts));
        Ev3MotorDriver driver = new Ev3MotorDriver(config(List.of("B", "C")), brick);
        MotorPlatform motors = new MotorPlatform(config(List.of("B", "C")), driver);
        driver.poll(motors.feedback());
        assertEquals("0D 00 2A 00 00 08 00 B3 00 01 60 B3 00 02 64", hex(link.eachWrite().get(0)));
        assertEquals(360, motors.motorDegrees("B"));
        assertEquals(-90, motors.motorDegrees("C"));
    }

    @Test
    void shouldClearCountsOfAllMotorsInOneInstruction() throws IOException {
        Ev3Brick brick = brick(Ev3PlatformTest::emptyReply);
        new Ev3MotorDriver(config(List.of("B", "C")), brick).clearCounts();
        assertEquals("08 00 2A 00 00 00 00 B2 00 06", hex(link.eachWrite().get(0)));
    }

    @Test
    void shouldSendStatesAsOneRequest() throws IOException {
        Ev3Brick brick = brick(Ev3PlatformTest::emptyReply);
        Ev3MotorDriver driver = new Ev3MotorDriver(config(List.of("B", "C")), brick);
        driver.send(List.of(MotorState.stopped("B", MotorState.StopMode.BRAKE)), new MotorPlatform(config(List.of("B", "C")), driver).feedback());
        assertEquals("09 00 2A 00 00 00 00 A3 00 02 01", hex(link.eachWrite().get(0)));
    }

    // ---- sensors ----

    private static SensorChannel channel(SensorType type, String port, Map<String, Object> options) {
        return new SensorChannel("s", type, port, options);
    }

    @ParameterizedTest(name = "{0} -> type {1} mode {2}")
    @CsvSource({"TOUCH, 16, 0", "LIGHT, 29, 0", "COLOR, 29, 2", "SONAR, 30, 0", "GYRO, 32, 0", "INFRARED, 33, 0"})
    void shouldPickDeviceTypeAndModeBySensorType(SensorType type, int device, int mode) {
        assertEquals(new Ev3SensorPlatform.Setup(device, mode, Ev3SensorPlatform.Reading.SI), Ev3SensorPlatform.setup(channel(type, "S1", Map.of())));
    }

    @Test
    void shouldTakeTypeModeAndRawReadingFromOptions() {
        assertEquals(new Ev3SensorPlatform.Setup(29, 1, Ev3SensorPlatform.Reading.SI),
                Ev3SensorPlatform.setup(channel(SensorType.LIGHT, "S1", Map.of("ev3_mode", 1))));
        assertEquals(new Ev3SensorPlatform.Setup(4, 0, Ev3SensorPlatform.Reading.RAW),
                Ev3SensorPlatform.setup(channel(SensorType.SOUND, "S1", Map.of("ev3_type", 4, "ev3_value", "raw"))));
    }

    @Test
    void shouldRefuseSensorTypeWithoutEv3SensorNamingTheSensorAndTheFix() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> Ev3SensorPlatform.setup(channel(SensorType.COMPASS, "S1", Map.of())));
        assertTrue(e.getMessage().contains("'s'") && e.getMessage().contains("ev3_type"), e.getMessage());
        assertThrows(IllegalArgumentException.class, () -> Ev3SensorPlatform.setup(channel(SensorType.TOUCH, "S1", Map.of("ev3_mode", 9))));
        assertThrows(IllegalArgumentException.class, () -> Ev3SensorPlatform.setup(channel(SensorType.TOUCH, "S1", Map.of("ev3_value", "pct"))));
    }

    @Test
    void shouldReadSensorWithReadySiAndSetItUpWhenCreated() throws Exception {
        byte[] cm = new byte[4];
        LittleEndian.putF32(cm, 0, 43.3f);
        Ev3Brick brick = brick(f -> replyWithGlobals(f, cm));
        Ev3SensorPlatform sensors = new Ev3SensorPlatform(new MotorPlatform(config(List.of()), new Ev3MotorDriver(config(List.of()), brick)), brick);
        Sensor sonar = sensors.createSensor(channel(SensorType.SONAR, "S4", Map.of()));
        assertEquals("0D 00 2A 00 00 04 00 99 1D 00 03 1E 00 01 60", hex(link.eachWrite().get(0)));
        assertEquals(43.3, sonar.readRaw().get(), 1e-5);
        assertEquals(2, link.writes());
    }

    @Test
    void shouldReadRawWithReadyRaw() throws Exception {
        byte[] mm = new byte[4];
        LittleEndian.putU32(mm, 0, 433);
        Ev3Brick brick = brick(f -> replyWithGlobals(f, mm));
        Ev3SensorPlatform sensors = new Ev3SensorPlatform(new MotorPlatform(config(List.of()), new Ev3MotorDriver(config(List.of()), brick)), brick);
        Sensor sonar = sensors.createSensor(channel(SensorType.SONAR, "4", Map.of("ev3_value", "raw")));
        assertEquals("0D 00 2A 00 00 04 00 99 1C 00 03 1E 00 01 60", hex(link.eachWrite().get(0)));
        assertEquals(433, sonar.readRaw().get());
    }

    @Test
    void shouldFailReadOfMissingValueNamingThePort() throws Exception {
        byte[] nan = new byte[4];
        LittleEndian.putF32(nan, 0, Float.NaN);
        Ev3Brick brick = brick(f -> replyWithGlobals(f, nan));
        Ev3SensorPlatform sensors = new Ev3SensorPlatform(new MotorPlatform(config(List.of()), new Ev3MotorDriver(config(List.of()), brick)), brick);
        Sensor touch = sensors.createSensor(channel(SensorType.TOUCH, "S2", Map.of()));
        ExecutionException e = assertThrows(ExecutionException.class, () -> touch.readRaw().get());
        assertInstanceOf(RobotException.class, e.getCause());
        assertTrue(e.getCause().getMessage().contains("S2") && e.getCause().getMessage().contains("NaN"), e.getCause().getMessage());
    }

    @Test
    void shouldRefuseInputPortsTheEv3DoesNotHave() throws IOException {
        Ev3Brick brick = brick(Ev3PlatformTest::emptyReply);
        Ev3SensorPlatform sensors = new Ev3SensorPlatform(new MotorPlatform(config(List.of()), new Ev3MotorDriver(config(List.of()), brick)), brick);
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> sensors.createSensor(channel(SensorType.TOUCH, "S5", Map.of())));
        assertTrue(e.getMessage().contains("'S5'"), e.getMessage());
    }
}
