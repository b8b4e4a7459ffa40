package io.robomw.platform.ft.txt;

import io.robomw.api.Clock;
import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.api.spi.ConnectionSettings;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.platform.sensor.Sensor;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import java.io.IOException;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.locks.LockSupport;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The TXT driver's motor and sensor platforms against a scripted TXT on 127.0.0.1: the handshake,
 * what each motor state puts in the exchange, how counter pulses become signed encoder degrees,
 * and how inputs are configured and read.
 */
class TxtDriverTest {

    private static final int TICKS = 63;
    private static final MotorState.StopMode BRAKE = MotorState.StopMode.BRAKE;

    private FakeTxt txt;
    private BrickChannel channel;
    private TxtController controller;
    private TxtMotorDriver driver;
    private MotorPlatform motors;

    @AfterEach
    void close() throws Exception {
        if (channel != null) {
            channel.close();
        }
        if (txt != null) {
            txt.close();
        }
    }

    private void open(Optional<String> leftCounter, Optional<String> rightCounter, List<SensorChannel> sensors) throws IOException {
        txt = new FakeTxt();
        ConnectionSettings connection = new ConnectionSettings(Map.of("host", "127.0.0.1", "port", txt.port()), "txt-test.yaml");
        List<MotorChannel> wheels = List.of(new MotorChannel("M1", MotorChannel.Role.LEFT_WHEEL, TICKS, leftCounter),
                new MotorChannel("M2", MotorChannel.Role.RIGHT_WHEEL, TICKS, rightCounter));
        PlatformConfig config = new PlatformConfig("txt-test", "ft-txt", connection, wheels, sensors, Duration.ofMillis(10), Duration.ZERO,
                Clock.system(), io.robomw.api.spi.PlatformServices.none(), io.robomw.api.spi.Cycling.OWN_THREADS, io.robomw.api.spi.FailurePolicy.logging());
        channel = BrickChannel.open("txt-test", connection, SerialSettings.of(115200, 8, SerialSettings.Parity.NONE, 1),
                TxtProtocol.TCP_PORT, Duration.ofMillis(500));
        controller = new TxtController("txt-test", channel);
        controller.open();
        driver = new TxtMotorDriver(config, controller);
        motors = new MotorPlatform(config, driver);
    }

    private void open() throws IOException {
        open(Optional.of("C1"), Optional.empty(), List.of());
    }

    private static double degrees(int pulses) {
        return pulses * 360.0 / TICKS;
    }

    @Test
    void shouldRunTheHandshakeBeforeAnythingElse() throws Exception {
        open();
        assertEquals(List.of(TxtProtocol.QUERY_STATUS, TxtProtocol.START_ONLINE, TxtProtocol.UPDATE_CONFIG), txt.requestIds());
        assertEquals("FakeTXT", controller.status().deviceName());
        TxtProtocol.Config config = txt.lastConfig();
        assertArrayEquals(new int[]{1, 1, 1, 1}, config.motor(), "every output drives a motor");
        assertArrayEquals(new int[]{1, 1, 1, 1, 1, 1, 1, 1}, config.inputDigital(), "inputs are switches until configured");
    }

    @Test
    void shouldSendALimitedPairAsDistanceCommandsInStep() throws Exception {
        open();
        driver.send(List.of(new MotorState("M1", 310, 1023.1, BRAKE), new MotorState("M2", 310, 1023.1, BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        TxtProtocol.Exchange x = txt.lastExchange();
        assertArrayEquals(new int[]{256, 0, 256, 0, 0, 0, 0, 0}, x.pwm(), "310 °/s is half of 620: PWM 256 forward");
        assertArrayEquals(new int[]{179, 179, 0, 0}, x.motorDist(), "1023.1° × 63 / 360 = 179 pulses");
        assertArrayEquals(new int[]{2, 1, 0, 0}, x.motorSync());
        assertArrayEquals(new int[]{1, 1, 0, 0}, x.motorCmdId(), "a new command id starts each distance command");
    }

    @Test
    void shouldDriveReverseOnTheOddOutputWithoutALimit() throws Exception {
        open();
        driver.send(List.of(new MotorState("M2", -700, Double.POSITIVE_INFINITY, BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        TxtProtocol.Exchange x = txt.lastExchange();
        assertArrayEquals(new int[]{0, 0, 0, 512, 0, 0, 0, 0}, x.pwm(), "beyond full speed is full power");
        assertArrayEquals(new int[4], x.motorDist());
        assertArrayEquals(new int[4], x.motorSync());
        driver.send(List.of(MotorState.stopped("M2", BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        assertArrayEquals(new int[8], txt.lastExchange().pwm());
        assertArrayEquals(new int[]{0, 2, 0, 0}, txt.lastExchange().motorCmdId(), "a stop ends the command, as ftrobopy's stop() does");
    }

    @Test
    void shouldKeepTheSmallestSpeedRunning() {
        assertEquals(1, TxtMotorDriver.pwm(0.1));
        assertEquals(0, TxtMotorDriver.pwm(0));
        assertEquals(512, TxtMotorDriver.pwm(-620));
        assertEquals(1, TxtMotorDriver.distancePulses(1, TICKS));
        assertEquals(0, TxtMotorDriver.distancePulses(1e6, TICKS), "too far for the s16 field: no controller stop");
    }

    @Test
    void shouldSignCounterPulsesByTheDirectionDriven() throws Exception {
        open();
        driver.exchangeNow(motors.feedback());
        driver.send(List.of(new MotorState("M1", 310, Double.POSITIVE_INFINITY, BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        txt.counter(0, 10);
        driver.exchangeNow(motors.feedback());
        assertEquals(degrees(10), motors.motorDegrees("M1"), 1e-9);
        driver.send(List.of(new MotorState("M1", -310, Double.POSITIVE_INFINITY, BRAKE)), motors.feedback());
        txt.counter(0, 12);
        driver.exchangeNow(motors.feedback());
        assertEquals(degrees(12), motors.motorDegrees("M1"), 1e-9, "pulses before the reversal still count forward");
        txt.counter(0, 18);
        driver.exchangeNow(motors.feedback());
        assertEquals(degrees(6), motors.motorDegrees("M1"), 1e-9, "the counter counts up; the platform counts back");
    }

    @Test
    void shouldFollowTheCounterAcrossTheSixteenBitWrap() throws Exception {
        open();
        txt.counter(1, 32760);
        driver.exchangeNow(motors.feedback());
        driver.send(List.of(new MotorState("M2", 310, Double.POSITIVE_INFINITY, BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        txt.counter(1, -32766);
        driver.exchangeNow(motors.feedback());
        assertEquals(degrees(10), motors.motorDegrees("M2"), 1e-9);
    }

    @Test
    void shouldStartCountingAgainWhenANewSessionBegins() throws Exception {
        open();
        driver.send(List.of(new MotorState("M1", 310, Double.POSITIVE_INFINITY, BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        txt.counter(0, 20);
        driver.exchangeNow(motors.feedback());
        txt.dropClient();
        txt.counter(0, 3);
        int[] failures = new int[1];
        Await.until("the driver reconnects", Duration.ofSeconds(5), () -> {
            try {
                driver.exchangeNow(motors.feedback());
                return true;
            } catch (IOException e) {
                failures[0]++;
                try {
                    channel.reopen(); // what the link agent does while the link is down
                } catch (IOException notYet) {
                    // the next try reopens again
                }
                return false;
            }
        });
        assertTrue(failures[0] > 0, "the dropped connection was noticed");
        long handshakes = txt.requestIds().stream().filter(id -> id == TxtProtocol.START_ONLINE).count();
        assertEquals(2, handshakes, "the new connection got its own handshake");
        assertEquals(degrees(20), motors.motorDegrees("M1"), 1e-9, "the restarted counter's first reading is a new base");
        txt.counter(0, 5);
        driver.exchangeNow(motors.feedback());
        assertEquals(degrees(22), motors.motorDegrees("M1"), 1e-9);
    }

    @Test
    void shouldLeaveTheStopToThePlatformForAWheelOnAnotherCounter() throws Exception {
        open(Optional.of("C3"), Optional.of("C1"), List.of());
        assertTrue(motors.hasEncoder("M1"));
        driver.send(List.of(new MotorState("M1", 310, 360, BRAKE), new MotorState("M2", 310, 360, BRAKE)), motors.feedback());
        driver.exchangeNow(motors.feedback());
        assertArrayEquals(new int[4], txt.lastExchange().motorDist(), "the TXT's distance command watches Ci for Mi only");
        txt.counter(2, 7);
        driver.exchangeNow(motors.feedback());
        assertEquals(degrees(7), motors.motorDegrees("M1"), 1e-9, "M1 is counted on C3");
        assertEquals(0, motors.motorDegrees("M2"), 1e-9);
    }

    @Test
    void shouldRefuseACounterThatIsNotC1ToC4() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> open(Optional.of("E1"), Optional.empty(), List.of()));
        assertTrue(e.getMessage().contains("txt-test.yaml") && e.getMessage().contains("C1 to C4"), e.getMessage());
    }

    private static SensorChannel sensor(String name, SensorType type, String port, Map<String, Object> options) {
        return new SensorChannel(name, type, port, options);
    }

    @Test
    void shouldConfigureEachSensorsInputAndReadIt() throws Exception {
        SensorChannel bumper = sensor("bumper", SensorType.TOUCH, "I1", Map.of());
        SensorChannel sonar = sensor("sonar", SensorType.SONAR, "I2", Map.of());
        SensorChannel photo = sensor("photo", SensorType.LIGHT, "I8", Map.of("input", "resistance"));
        open(Optional.of("C1"), Optional.empty(), List.of(bumper, sonar, photo));
        TxtSensorPlatform sensors = new TxtSensorPlatform(motors, driver, controller);
        Sensor b = sensors.createSensor(bumper);
        Sensor s = sensors.createSensor(sonar);
        Sensor p = sensors.createSensor(photo);
        TxtProtocol.Config config = txt.lastConfig();
        assertArrayEquals(new int[]{1, 3, 1, 1, 1, 1, 1, 1}, config.inputMode());
        assertArrayEquals(new int[]{1, 0, 1, 1, 1, 1, 1, 0}, config.inputDigital());
        txt.input(0, 1);
        txt.input(1, 42);
        txt.input(7, 4700);
        assertEquals(1.0, b.readRaw().get());
        assertEquals(42.0, s.readRaw().get());
        assertEquals(4700.0, p.readRaw().get());
    }

    @Test
    void shouldRefuseSensorsTheInputsCannotRead() throws Exception {
        open();
        TxtSensorPlatform sensors = new TxtSensorPlatform(motors, driver, controller);
        IOException gyro = assertThrows(IOException.class, () -> sensors.createSensor(sensor("g", SensorType.GYRO, "I1", Map.of())));
        assertTrue(gyro.getMessage().contains("GYRO"), gyro.getMessage());
        IOException port = assertThrows(IOException.class, () -> sensors.createSensor(sensor("t", SensorType.TOUCH, "S1", Map.of())));
        assertTrue(port.getMessage().contains("I1 to I8"), port.getMessage());
        IOException mode = assertThrows(IOException.class, () -> sensors.createSensor(sensor("t", SensorType.TOUCH, "I1",
                Map.of("input", "capacitive"))));
        assertTrue(mode.getMessage().contains("capacitive"), mode.getMessage());
    }

    @Test
    void shouldFailAReadWithRobotLinkExceptionWhenTheTxtIsGone() throws Exception {
        SensorChannel bumper = sensor("bumper", SensorType.TOUCH, "I1", Map.of());
        open(Optional.of("C1"), Optional.empty(), List.of(bumper));
        Sensor b = new TxtSensorPlatform(motors, driver, controller).createSensor(bumper);
        txt.close();
        long deadline = System.nanoTime() + Duration.ofSeconds(5).toNanos();
        ExecutionException e = null;
        while (e == null) {
            try {
                b.readRaw().get();
                assertTrue(System.nanoTime() < deadline, "reads kept succeeding after the TXT went away");
                LockSupport.parkNanos(10_000_000);
            } catch (ExecutionException failed) {
                e = failed;
            }
        }
        assertInstanceOf(RobotLinkException.class, e.getCause());
        assertTrue(e.getCause().getMessage().contains("bumper"), e.getCause().getMessage());
        assertFalse(controller.isOnline());
    }
}
