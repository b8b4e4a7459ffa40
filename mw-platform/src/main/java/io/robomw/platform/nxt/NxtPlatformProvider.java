package io.robomw.platform.nxt;

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
 * {@code platform: nxt}: a LEGO Mindstorms NXT over a serial link (a Bluetooth-paired brick is
 * {@code /dev/rfcomm0} or {@code COM5}) or a TCP bridge. Connection keys: {@code port} (device
 * path) and {@code baud}, or {@code host} and {@code port}; {@code reply_timeout_ms} (default
 * {@value #DEFAULT_REPLY_TIMEOUT_MS}); {@code wire_log} (a file that records every byte).
 */
public final class NxtPlatformProvider implements PlatformProvider {

    /**
     * How long each reply is awaited by default, milliseconds: as the EV3's. A Bluetooth round trip
     * takes about 30 ms; 300 ms, the old default, took a loaded host held up for a moment for a dead
     * link. A link that is really gone (the brick switched off, the serial device closed) fails at
     * once.
     */
    public static final int DEFAULT_REPLY_TIMEOUT_MS = 500;

    @Override
    public String platformName() {
        return "nxt";
    }

    @Override
    public List<String> check(PlatformConfig config) {
        return new PlatformCheck(config).connectionHasOneOf("port", "host")
                .motorPorts(NxtMotorDriver::outputPort)
                .sensors(NxtSensorPlatform::inputPort, NxtSensorPlatform.SUPPORTED, "the NXT", null)
                .problems();
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", DEFAULT_REPLY_TIMEOUT_MS));
        BrickChannel channel = BrickChannel.open(config.robotName(), config.connection(),
                SerialSettings.of(115200, 8, SerialSettings.Parity.NONE, 1), 0, timeout);
        try {
            NxtBrick brick = new NxtBrick(config.robotName(), channel);
            NxtMotorDriver driver = new NxtMotorDriver(config, brick);
            driver.resetCounters();
            MotorPlatform motors = new MotorPlatform(config, driver);
            return new BrickPlatform(config, motors, new NxtSensorPlatform(motors, brick), channel, null).start();
        } catch (IOException | RuntimeException e) {
            channel.close();
            throw e;
        }
    }
}
