package io.robomw.api.spi;

import java.io.IOException;

/**
 * A robot platform (a brick driver, the simulator), found through
 * {@link java.util.ServiceLoader} by the {@code platform:} value of a robot description. To add a
 * platform, implement this, list the class in
 * {@code META-INF/services/io.robomw.api.spi.PlatformProvider}, and put the jar on the class path.
 */
public interface PlatformProvider {

    /** @return the {@code platform:} value this provider answers to, for example {@code nxt} */
    String platformName();

    /**
     * Opens the link to one robot and starts its platform (execution action thread, I/O).
     *
     * @param config what the description says about this robot's hardware
     * @return the running platform; the caller closes it
     * @throws IOException if the link cannot be opened; the message names the port or address
     */
    RobotPlatform open(PlatformConfig config) throws IOException;
}
