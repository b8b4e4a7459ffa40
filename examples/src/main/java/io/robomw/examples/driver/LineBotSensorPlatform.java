package io.robomw.examples.driver;

import io.robomw.api.RobotLinkException;
import io.robomw.api.SensorType;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;

import java.io.IOException;
import java.util.EnumSet;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

/**
 * The LineBot's sensors: a ranger (sonar or infrared: centimetres) or a switch (touch: 1 pressed)
 * on input 1 or 2, read with {@code READ i} on the caller's thread, one exchange at a time on the
 * board's channel. The raw value goes up as it is; the robot file converts it (a ranger's
 * {@code scale: 0.01} gives metres).
 */
public final class LineBotSensorPlatform extends SensorPlatform {

    /** The sensor types the LineBot's inputs read. */
    static final Set<SensorType> SUPPORTED = EnumSet.of(SensorType.SONAR, SensorType.INFRARED, SensorType.TOUCH);

    private final LineBot bot;

    /**
     * @param motors the motor platform (for the encoders as tacho sensors)
     * @param bot    the board
     */
    public LineBotSensorPlatform(MotorPlatform motors, LineBot bot) {
        super(motors);
        this.bot = bot;
    }

    @Override
    public Sensor createSensor(SensorChannel sensor) throws IOException {
        int input;
        try {
            input = LineBotProtocol.input(sensor.port());
        } catch (IllegalArgumentException e) {
            throw new IOException("robot '" + bot.robot() + "': sensor '" + sensor.name() + "': " + e.getMessage(), e);
        }
        if (!SUPPORTED.contains(sensor.type())) {
            throw new IOException("robot '" + bot.robot() + "': sensor '" + sensor.name() + "': the LineBot's inputs read a sonar, an infrared"
                    + " ranger or a touch switch, not a " + sensor.type().name().toLowerCase(java.util.Locale.ROOT) + " sensor");
        }
        return () -> read(sensor.name(), input);
    }

    private CompletableFuture<Double> read(String name, int input) {
        try {
            return CompletableFuture.completedFuture((double) bot.read(input));
        } catch (IOException e) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + bot.robot() + "': reading sensor '" + name + "' on input "
                    + input + " failed: " + e.getMessage(), e));
        } catch (RuntimeException e) {
            return CompletableFuture.failedFuture(e);
        }
    }
}
