package io.robomw.platform;

import io.robomw.api.SensorType;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.SensorChannel;

import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.function.Consumer;

/**
 * Collects what a driver's {@link io.robomw.api.spi.PlatformProvider#check} finds: each check is
 * one of the driver's own port parsers or setups, run without a link, and each
 * {@link IllegalArgumentException} it throws becomes one problem. Checks that every brick shares
 * (a connection to open, encoder sensors on motor ports) are here too.
 */
public final class PlatformCheck {

    private final PlatformConfig config;
    private final List<String> problems = new ArrayList<>();

    /**
     * @param config the robot's platform configuration
     */
    public PlatformCheck(PlatformConfig config) {
        this.config = config;
    }

    /**
     * @param check a check that throws {@link IllegalArgumentException} with a message for the user
     * @return this
     */
    public PlatformCheck run(Runnable check) {
        try {
            check.run();
        } catch (IllegalArgumentException e) {
            problems.add(e.getMessage());
        }
        return this;
    }

    /**
     * @param portCheck the driver's motor port parser
     * @return this, with a problem per motor port the brick does not have
     */
    public PlatformCheck motorPorts(Consumer<String> portCheck) {
        for (String port : config.motorPorts()) {
            run(() -> portCheck.accept(port));
        }
        return this;
    }

    /**
     * Checks every sensor but the motors' encoders ({@link SensorType#TACHO}, which must be on a
     * motor port of the robot).
     *
     * @param portCheck the driver's input port parser
     * @param supported the sensor types the brick reads, or {@code null} when its check of a sensor is its own
     * @param name      the brick's name in messages, e.g. "the NXT"
     * @param also      further checks of a sensor (options), or {@code null}
     * @return this
     */
    public PlatformCheck sensors(Consumer<String> portCheck, Set<SensorType> supported, String name, Consumer<SensorChannel> also) {
        for (SensorChannel s : config.sensors()) {
            if (s.type() == SensorType.TACHO) {
                if (!config.motorPorts().contains(s.port())) {
                    problems.add("sensor '" + s.name() + "': an encoder (tacho) sensor reads a motor of the robot, and '" + s.port() + "' is none ("
                            + String.join(", ", config.motorPorts()) + ")");
                }
                continue;
            }
            run(() -> portCheck.accept(s.port()));
            if (supported != null && !supported.contains(s.type())) {
                problems.add("sensor '" + s.name() + "': " + name + " has no standard " + s.type().name().toLowerCase(java.util.Locale.ROOT)
                        + " sensor (it reads " + String.join(", ", supported.stream().map(t -> t.name().toLowerCase(java.util.Locale.ROOT)).sorted().toList())
                        + ")");
            }
            if (also != null) {
                run(() -> also.accept(s));
            }
        }
        return this;
    }

    /**
     * @param keys the connection keys of which one is needed, e.g. {@code port} or {@code host}
     * @return this, with a problem when none is given
     */
    public PlatformCheck connectionHasOneOf(String... keys) {
        for (String k : keys) {
            if (config.connection().text(k).isPresent()) {
                return this;
            }
        }
        problems.add("the connection gives none of " + String.join(", ", keys) + " (a serial device such as /dev/rfcomm0, or a host and port)");
        return this;
    }

    /**
     * @param problem a problem found by the driver itself
     * @return this
     */
    public PlatformCheck problem(String problem) {
        problems.add(problem);
        return this;
    }

    /** @return the problems found, in order */
    public List<String> problems() {
        return List.copyOf(problems);
    }
}
