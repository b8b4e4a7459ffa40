package io.robomw.cli.robot;

import io.robomw.api.spi.MotorCommand;
import io.robomw.api.spi.MotorTarget;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;

import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;

/**
 * A test platform ({@code platform: test-instant}) whose motors reach their targets at once and
 * whose sensors all read 42 (raw). Enough to serve a real {@code ConfiguredRobot} in tests.
 */
public final class InstantPlatform implements RobotPlatform {

    private final Map<String, Double> degrees = new ConcurrentHashMap<>();

    /** Registered in META-INF/services for {@code platform: test-instant}. */
    public static final class Provider implements PlatformProvider {
        @Override
        public String platformName() {
            return "test-instant";
        }

        @Override
        public RobotPlatform open(PlatformConfig config) {
            InstantPlatform p = new InstantPlatform();
            config.motorPorts().forEach(port -> p.degrees.put(port, 0.0));
            return p;
        }
    }

    @Override
    public CompletableFuture<Void> run(MotorCommand command) {
        for (MotorTarget t : command.targets()) {
            if (!t.continuous()) {
                degrees.merge(t.port(), Math.copySign(t.degrees(), t.degreesPerSecond()), Double::sum);
            }
        }
        return CompletableFuture.completedFuture(null);
    }

    @Override
    public CompletableFuture<Void> stopAll() {
        return CompletableFuture.completedFuture(null); // nothing moves between commands
    }

    @Override
    public CompletableFuture<Double> readRaw(String sensorName) {
        return CompletableFuture.completedFuture(42.0);
    }

    @Override
    public double motorDegrees(String port) {
        return degrees.getOrDefault(port, 0.0);
    }

    @Override
    public boolean hasEncoder(String port) {
        return degrees.containsKey(port);
    }

    @Override
    public void close() {
        degrees.clear();
    }
}
