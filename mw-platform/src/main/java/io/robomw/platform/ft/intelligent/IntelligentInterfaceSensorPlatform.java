package io.robomw.platform.ft.intelligent;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;

import java.io.IOException;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;

/**
 * The Intelligent Interface's sensors: a switch on a digital input E1..E8 reads 1 when closed; a
 * sensor on EX or EY reads the 10-bit analog value (convert it in the robot file). The interface is
 * polled every cycle anyway, so a read returns the latest poll's value at once; one older than
 * {@link #STALE} means the link is down, and the read fails with {@link RobotLinkException}.
 */
public final class IntelligentInterfaceSensorPlatform extends SensorPlatform {

    /** Age after which polled inputs are no longer believed. */
    public static final Duration STALE = Duration.ofSeconds(1);

    private final String robot;
    private final IntelligentInterfaceInputs inputs;

    /**
     * @param robot  the robot's name, for messages
     * @param motors the motor platform
     * @param inputs the inputs the motor platform publishes
     */
    public IntelligentInterfaceSensorPlatform(String robot, MotorPlatform motors, IntelligentInterfaceInputs inputs) {
        super(motors);
        this.robot = robot;
        this.inputs = inputs;
    }

    @Override
    public Sensor createSensor(SensorChannel sensor) throws IOException {
        int bit = IntelligentInterfaceTelegram.digitalInput(sensor.port());
        if (bit >= 0) {
            return () -> read(sensor, s -> (s.digital() >> bit) & 1);
        }
        if (sensor.port().equals("EX")) {
            return () -> read(sensor, IntelligentInterfaceInputs.Snapshot::ex);
        }
        if (sensor.port().equals("EY")) {
            return () -> read(sensor, IntelligentInterfaceInputs.Snapshot::ey);
        }
        throw new IOException("robot '" + robot + "': sensor '" + sensor.name() + "' is on port '" + sensor.port()
                + "'; the Intelligent Interface has digital inputs E1 to E8 and analog inputs EX and EY");
    }

    private CompletableFuture<Double> read(SensorChannel sensor, java.util.function.ToIntFunction<IntelligentInterfaceInputs.Snapshot> field) {
        IntelligentInterfaceInputs.Snapshot s = inputs.latest();
        if (s == null) {
            return inputs.firstPoll().orTimeout(STALE.toMillis(), java.util.concurrent.TimeUnit.MILLISECONDS)
                    .handle((v, e) -> e)
                    .thenCompose(e -> e == null ? read(sensor, field) : CompletableFuture.failedFuture(new RobotLinkException(
                            "robot '" + robot + "': the Intelligent Interface has not answered a poll yet", e)));
        }
        if (inputs.ageNanos(s) > STALE.toNanos() || field.applyAsInt(s) < 0) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + robot + "': no fresh reading of '" + sensor.name()
                    + "' from the Intelligent Interface (none within " + STALE.toMillis() + " ms); is its link up?", null));
        }
        return CompletableFuture.completedFuture((double) field.applyAsInt(s));
    }
}
