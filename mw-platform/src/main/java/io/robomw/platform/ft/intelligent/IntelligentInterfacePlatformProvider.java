package io.robomw.platform.ft.intelligent;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.PlatformCheck;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.motor.MotorPlatform;

import java.io.IOException;
import java.time.Duration;
import java.util.List;

/**
 * {@code platform: ft-intelligent}: a fischertechnik Intelligent Interface 30402 on a serial port
 * (9600 8N1). Connection keys: {@code port}, {@code reply_timeout_ms} (default {@value #DEFAULT_REPLY_TIMEOUT_MS}),
 * {@code pulse_ms} (default 5: over a TCP bridge, the shortest time a pulsed wheel motor is on), {@code wire_log}. Keep {@code cycle_hz} at 20 or more: the interface stops its motors when it
 * hears nothing for 300 ms, and the platform refreshes it once a cycle.
 */
public final class IntelligentInterfacePlatformProvider implements PlatformProvider {

    /**
     * How long each answer is awaited by default, milliseconds. The interface answers within a few
     * milliseconds, and stops its motors by itself 300 ms after the last command, so the timeout
     * only decides how soon a dead link is reported; a second keeps a loaded host (or an emulator
     * on one) that is held up for a few hundred milliseconds from being taken for a dead link.
     */
    public static final int DEFAULT_REPLY_TIMEOUT_MS = 1000;

    @Override
    public String platformName() {
        return "ft-intelligent";
    }

    @Override
    public List<String> check(PlatformConfig config) {
        PlatformCheck check = new PlatformCheck(config).connectionHasOneOf("port", "host")
                .motorPorts(p -> FtMotors.index(p, IntelligentInterfaceTelegram.MOTORS))
                .sensors(p -> {
                    if (IntelligentInterfaceTelegram.digitalInput(p) < 0 && !p.equals("EX") && !p.equals("EY")) {
                        throw new IllegalArgumentException("the Intelligent Interface has digital inputs E1 to E8 and analog inputs EX and EY, not '" + p + "'");
                    }
                }, null, "the Intelligent Interface", null);
        for (io.robomw.api.spi.MotorChannel w : config.wheels()) {
            w.counter().filter(c -> IntelligentInterfaceTelegram.digitalInput(c) < 0).ifPresent(c ->
                    check.problem("wheel counter '" + c + "' must be a digital input of the Intelligent Interface, E1 to E8"));
        }
        if (config.cyclePeriod().compareTo(Duration.ofMillis(50)) > 0) {
            check.problem("cycle_hz must be at least 20 for an Intelligent Interface, which stops its motors after "
                    + IntelligentInterfaceTelegram.WATCHDOG_MILLIS + " ms without a command");
        }
        return check.problems();
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        if (config.cyclePeriod().compareTo(Duration.ofMillis(50)) > 0) {
            throw new IOException(config.source() + ": cycle_hz must be at least 20 for an Intelligent Interface, which stops its motors "
                    + "after " + IntelligentInterfaceTelegram.WATCHDOG_MILLIS + " ms without a command");
        }
        Duration timeout = Duration.ofMillis(config.connection().integer("reply_timeout_ms", DEFAULT_REPLY_TIMEOUT_MS));
        BrickChannel channel = BrickChannel.open(config.robotName(), config.connection(),
                SerialSettings.of(IntelligentInterfaceTelegram.BAUD, 8, SerialSettings.Parity.NONE, 1), 0, timeout);
        try {
            IntelligentInterfaceInputs inputs = new IntelligentInterfaceInputs(config.clock());
            MotorPlatform motors = new MotorPlatform(config, new IntelligentInterfaceMotorDriver(config, channel, inputs));
            return new BrickPlatform(config, motors, new IntelligentInterfaceSensorPlatform(config.robotName(), motors, inputs),
                    channel, null).start();
        } catch (IOException | RuntimeException e) {
            channel.close();
            throw e;
        }
    }
}
