package io.robomw.platform.rcx;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.motor.MotorPlatform;

import java.io.IOException;
import java.time.Duration;

/**
 * {@code platform: rcx}: a LEGO Mindstorms RCX (RIS 1.x/2.0 firmware) through the serial IR tower
 * (2400 baud, 8 data bits, odd parity, 1 stop bit). Connection keys: {@code port} (the tower's
 * serial device) and {@code baud}, or {@code host} and {@code port} for a TCP bridge;
 * {@code echo} (default true: the serial tower hears its own packets; false for a tower that does
 * not); {@code reply_timeout_ms} (default 500: a packet, its echo and the reply take about
 * 120 ms at 2400 baud); {@code wire_log}. Keep the brick within the tower's sight.
 */
public final class RcxPlatformProvider implements PlatformProvider {

    /** The tower's line: 2400 baud, 8 data bits, odd parity, 1 stop bit. */
    public static final SerialSettings TOWER = SerialSettings.of(2400, 8, SerialSettings.Parity.ODD, 1);

    @Override
    public String platformName() {
        return "rcx";
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", 500));
        boolean echo = config.connection().bool("echo", true);
        BrickChannel channel = BrickChannel.open(config.robotName(), config.connection(), TOWER, 0, timeout);
        try {
            RcxBrick brick = new RcxBrick(config.robotName(), channel, echo);
            brick.alive();
            RcxMotorDriver driver = new RcxMotorDriver(config, brick);
            driver.setUp();
            MotorPlatform motors = new MotorPlatform(config, driver);
            return new BrickPlatform(config, motors, new RcxSensorPlatform(motors, brick), channel, null).start();
        } catch (IOException | RuntimeException e) {
            channel.close();
            throw e;
        }
    }
}
