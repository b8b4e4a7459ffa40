package io.robomw.platform.aibo;

import io.robomw.api.Clock;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;

import java.time.Duration;
import java.util.OptionalDouble;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * The Aibo's sensor platform. A sensor's {@code port} is the URBI device it reads
 * ({@code distanceNear}, {@code accelX}, {@code pawLF}, {@code legLF1}); its raw value is the
 * device's {@code val} in the device's own unit (millimetres for distances, m/s² for
 * accelerations, degrees for joints, 0 or 1 for touch), which the description's conversion turns
 * into SI units above this layer.
 *
 * <p>Each sensor is streamed when the robot opens ({@code s3: every(100ms) distanceNear.val,}),
 * so a read answers at once from the last streamed value while it is fresh (at most three
 * stream periods old); otherwise it asks the device itself ({@code r9: distanceNear.val,}) and
 * waits for the answer at most the reply timeout. An error from the robot fails the read with a
 * {@link RobotException} naming the device; no answer fails it with {@link RobotLinkException}.
 */
final class AiboSensorPlatform extends SensorPlatform {

    private final String robot;
    private final UrbiConnection connection;
    private final Clock clock;
    private final long streamMillis;

    /**
     * @param robot        the robot's name
     * @param connection   the URBI session
     * @param clock        the clock fresh values are timed on
     * @param streamPeriod how often each sensor is streamed; {@link Duration#ZERO} reads on demand only
     */
    AiboSensorPlatform(String robot, UrbiConnection connection, Clock clock, Duration streamPeriod) {
        this.robot = robot;
        this.connection = connection;
        this.clock = clock;
        this.streamMillis = streamPeriod.toMillis();
    }

    /** The last streamed value of a device, and when it came. */
    private record Reading(double value, long atNanos) {
    }

    @Override
    public Sensor createSensor(SensorChannel channel) throws java.io.IOException {
        String device = channel.port();
        try {
            UrbiProtocol.read("check", device);
        } catch (IllegalArgumentException e) {
            throw new java.io.IOException("robot '" + robot + "': sensor '" + channel.name() + "': port '" + device + "' is not an URBI device name ("
                    + e.getMessage() + ")", e);
        }
        Reading[] latest = new Reading[1];
        if (streamMillis > 0) {
            String tag = connection.newTag("s");
            connection.register(tag, reply -> {
                OptionalDouble v = reply.number();
                if (v.isPresent()) {
                    synchronized (latest) {
                        latest[0] = new Reading(v.getAsDouble(), clock.nanoTime());
                    }
                } else if (reply.kind() == UrbiReply.Kind.ERROR) {
                    org.slf4j.LoggerFactory.getLogger(AiboSensorPlatform.class).warn("robot '{}': streaming {}.val failed: {}", robot, device,
                            reply.describe());
                }
            });
            connection.addStream(UrbiProtocol.stream(tag, device, streamMillis));
        }
        long freshNanos = streamMillis * 3_000_000L;
        return () -> {
            Reading r;
            synchronized (latest) {
                r = latest[0];
            }
            if (r != null && clock.nanoTime() - r.atNanos() <= freshNanos) {
                return CompletableFuture.completedFuture(r.value());
            }
            return readNow(channel.name(), device);
        };
    }

    private CompletableFuture<Double> readNow(String sensor, String device) {
        CompletableFuture<Double> f = new CompletableFuture<>();
        String tag = connection.newTag("r");
        connection.register(tag, reply -> {
            if (reply.kind() == UrbiReply.Kind.ERROR) {
                f.completeExceptionally(new RobotException("robot '" + robot + "': reading sensor '" + sensor + "' (" + device + ".val) failed: "
                        + reply.describe()));
            } else {
                OptionalDouble v = reply.number();
                if (v.isPresent()) {
                    f.complete(v.getAsDouble());
                } else if (reply.kind() == UrbiReply.Kind.VALUE || reply.kind() == UrbiReply.Kind.BINARY) {
                    f.completeExceptionally(new RobotException("robot '" + robot + "': sensor '" + sensor + "' (" + device + ".val) answered "
                            + reply.describe() + ", not a number"));
                }
            }
        });
        if (!connection.send(UrbiProtocol.read(tag, device))) {
            connection.forget(tag);
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + robot + "': reading sensor '" + sensor + "': the link to "
                    + connection.describe() + (connection.isDown() ? " is down" : " is congested"), null));
        }
        Duration timeout = connection.replyTimeout();
        return f.orTimeout(timeout.toMillis(), TimeUnit.MILLISECONDS).handle((v, e) -> {
            connection.forget(tag);
            if (e == null) {
                return v;
            }
            Throwable cause = e instanceof java.util.concurrent.CompletionException && e.getCause() != null ? e.getCause() : e;
            if (cause instanceof TimeoutException) {
                String said = connection.lastUntaggedError();
                throw new RobotLinkException("robot '" + robot + "': sensor '" + sensor + "' (" + device + ".val) was not answered within "
                        + timeout.toMillis() + " ms on " + connection.describe() + (said.isEmpty() ? "" : "; the robot last said: !!! " + said), cause);
            }
            throw cause instanceof RuntimeException re ? re : new RobotException(cause.getMessage(), cause);
        });
    }
}
