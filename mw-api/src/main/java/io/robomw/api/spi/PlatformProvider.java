package io.robomw.api.spi;

import java.io.IOException;
import java.util.List;

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
     * Checks a robot's description against this platform without opening a link: the motor and
     * sensor port names it has, the sensor types it supports, the connection it needs. The
     * Configuration Layer runs it before {@link #open}, and {@code mw describe} runs it alone, so
     * a file that describes cleanly opens cleanly (as far as the file can tell).
     *
     * @param config what the description says about this robot's hardware
     * @return one sentence per problem, each naming the value that is wrong and what the platform
     *         has instead; empty when the description fits
     */
    default List<String> check(PlatformConfig config) {
        return List.of();
    }

    /**
     * Opens the link to one robot and starts its platform (execution action thread, I/O).
     *
     * @param config what the description says about this robot's hardware
     * @return the running platform; the caller closes it
     * @throws IOException if the link cannot be opened; the message names the port or address
     */
    RobotPlatform open(PlatformConfig config) throws IOException;
}
