package io.robomw.platform.ev3;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.PlatformCheck;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.motor.MotorPlatform;

import java.io.IOException;
import java.time.Duration;
import java.util.List;

/**
 * {@code platform: ev3}: a LEGO Mindstorms EV3 running the standard firmware, spoken to with
 * direct commands over a serial link (a Bluetooth-paired brick is {@code /dev/rfcomm0} or
 * {@code COM5}) or TCP (the brick emulator, or a bridge). Connection keys: {@code port} (device
 * path) and {@code baud}, or {@code host} and {@code port} (default {@value #TCP_PORT});
 * {@code reply_timeout_ms} (default {@value #DEFAULT_REPLY_TIMEOUT_MS}); {@code wire_log} (a file
 * that records every byte).
 */
public final class Ev3PlatformProvider implements PlatformProvider {

    /** The EV3's TCP port for direct commands. */
    public static final int TCP_PORT = 5555;
    /** How long each reply is awaited unless {@code reply_timeout_ms} says otherwise. */
    public static final int DEFAULT_REPLY_TIMEOUT_MS = 500;

    @Override
    public String platformName() {
        return "ev3";
    }

    @Override
    public List<String> check(PlatformConfig config) {
        return new PlatformCheck(config).connectionHasOneOf("port", "host")
                .motorPorts(Ev3Ports::outputNumber)
                .sensors(Ev3Ports::inputNumber, null, "the EV3", Ev3SensorPlatform::setup)
                .problems();
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", DEFAULT_REPLY_TIMEOUT_MS));
        BrickChannel channel = BrickChannel.open(config.robotName(), config.connection(),
                SerialSettings.of(115200, 8, SerialSettings.Parity.NONE, 1), TCP_PORT, timeout);
        try {
            Ev3Brick brick = new Ev3Brick(config.robotName(), channel);
            Ev3MotorDriver driver = new Ev3MotorDriver(config, brick);
            driver.clearCounts();
            MotorPlatform motors = new MotorPlatform(config, driver);
            return new BrickPlatform(config, motors, new Ev3SensorPlatform(motors, brick), channel, null).start();
        } catch (IOException | RuntimeException e) {
            channel.close();
            throw e;
        }
    }
}
