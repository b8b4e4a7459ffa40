package io.robomw.platform.ft.txt;

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
 * {@code platform: ft-txt}: a fischertechnik TXT controller in online mode over TCP. Connection
 * keys: {@code host} (192.168.7.2 over USB, 192.168.8.2 over WLAN, 192.168.9.2 over Bluetooth),
 * {@code port} (default 65000), {@code reply_timeout_ms} (default 500), {@code wire_log} (a file
 * that records every byte).
 *
 * <p>Opening runs the handshake (queryStatus, startOnline, updateConfig), configures each sensor's
 * input, sends one exchange with every motor off, then starts the platform; the link thread then
 * sends the exchange every cycle. Closing stops the motors and sends stopOnline.
 */
public final class TxtPlatformProvider implements PlatformProvider {

    /** Default {@code reply_timeout_ms}. */
    public static final int DEFAULT_REPLY_TIMEOUT_MS = 500;

    @Override
    public String platformName() {
        return "ft-txt";
    }

    @Override
    public List<String> check(PlatformConfig config) {
        PlatformCheck check = new PlatformCheck(config);
        if (config.connection().text("host").isEmpty()) {
            check.problem("the ft-txt platform talks TCP: give connection.host (192.168.7.2 over USB, 192.168.8.2 over WLAN, 192.168.9.2 over"
                    + " Bluetooth) and, if not " + TxtProtocol.TCP_PORT + ", connection.port");
        }
        return check.motorPorts(TxtPorts::motor)
                .run(() -> TxtPorts.wheelCounters(config.motors(), config.source()))
                .sensors(TxtPorts::input, null, "the TXT", TxtSensorPlatform::modeOf)
                .problems();
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        if (config.connection().text("host").isEmpty()) {
            throw new IOException(config.source() + ": the ft-txt platform talks TCP: give connection.host (192.168.7.2 over USB, "
                    + "192.168.8.2 over WLAN, 192.168.9.2 over Bluetooth) and, if not " + TxtProtocol.TCP_PORT + ", connection.port");
        }
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", DEFAULT_REPLY_TIMEOUT_MS));
        BrickChannel channel = BrickChannel.open(config.robotName(), config.connection(),
                SerialSettings.of(115200, 8, SerialSettings.Parity.NONE, 1), TxtProtocol.TCP_PORT, timeout);
        try {
            TxtController controller = new TxtController(config.robotName(), channel);
            controller.open();
            TxtMotorDriver driver = new TxtMotorDriver(config, controller);
            MotorPlatform motors = new MotorPlatform(config, driver);
            driver.exchangeNow(motors.feedback());
            AutoCloseable link = () -> {
                controller.stopOnline();
                channel.close();
            };
            return new BrickPlatform(config, motors, new TxtSensorPlatform(motors, driver, controller), channel, link).start();
        } catch (IOException | RuntimeException e) {
            channel.close();
            throw e;
        }
    }
}
