package io.robomw.api.spi;

import io.robomw.api.Robot;

import java.net.URI;

/**
 * Opens robots of one kind of address for {@link io.robomw.api.Robots}; found through
 * {@link java.util.ServiceLoader}. {@code mw-config} answers to {@code file}, {@code mw-agents} to
 * the messaging schemes.
 */
public interface RobotFactory {

    /** @return the URI scheme this factory opens, for example {@code file} or {@code tcp} */
    String scheme();

    /**
     * @param location the robot's address
     * @param services services for the platform
     * @return the open robot
     */
    Robot open(URI location, PlatformServices services);
}
