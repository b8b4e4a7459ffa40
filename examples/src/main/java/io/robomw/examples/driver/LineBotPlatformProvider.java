package io.robomw.examples.driver;

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
 * {@code platform: linebot}: the example driver of docs/writing-a-driver.md, for a made-up hobby
 * board that speaks the line protocol of {@link LineBotProtocol} over a serial port (or a TCP
 * bridge). Connection keys: {@code port} (device path) and {@code baud}, or {@code host} and
 * {@code port} (default {@value #TCP_PORT}); {@code reply_timeout_ms} (default
 * {@value #DEFAULT_REPLY_TIMEOUT_MS}); {@code wire_log}. Listed in
 * {@code META-INF/services/io.robomw.api.spi.PlatformProvider}.
 */
public final class LineBotPlatformProvider implements PlatformProvider {

    /** The TCP port of a bridge, when the connection gives a host but no port. */
    public static final int TCP_PORT = 7070;
    /** How long each reply is awaited unless {@code reply_timeout_ms} says otherwise. */
    public static final int DEFAULT_REPLY_TIMEOUT_MS = 500;

    @Override
    public String platformName() {
        return "linebot";
    }

    /** Motor ports A and B, sensors on inputs 1 and 2 of the types the inputs read, a connection to open. */
    @Override
    public List<String> check(PlatformConfig config) {
        return new PlatformCheck(config).connectionHasOneOf("port", "host")
                .motorPorts(LineBotProtocol::motor)
                .sensors(LineBotProtocol::input, LineBotSensorPlatform.SUPPORTED, "the LineBot", null)
                .problems();
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", DEFAULT_REPLY_TIMEOUT_MS));
        BrickChannel channel = BrickChannel.open(config.robotName(), config.connection(),
                SerialSettings.of(115200, 8, SerialSettings.Parity.NONE, 1), TCP_PORT, timeout);
        try {
            LineBot bot = new LineBot(config.robotName(), channel);
            bot.hello();
            LineBotMotorDriver driver = new LineBotMotorDriver(config, bot);
            driver.zero();
            MotorPlatform motors = new MotorPlatform(config, driver);
            return new BrickPlatform(config, motors, new LineBotSensorPlatform(motors, bot), channel, null).start();
        } catch (IOException | RuntimeException e) {
            channel.close();
            throw e;
        }
    }
}
