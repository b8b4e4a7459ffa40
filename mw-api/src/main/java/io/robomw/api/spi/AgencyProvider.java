package io.robomw.api.spi;

/**
 * Gives robots their agency; found through {@link java.util.ServiceLoader}
 * ({@code META-INF/services/io.robomw.api.spi.AgencyProvider}). {@code mw-agents} provides one.
 */
public interface AgencyProvider {

    /**
     * Opens one robot's agency; its home starts on first use.
     *
     * @param config the robot's agency settings
     * @return the component
     */
    AgencyComponent open(AgencyConfig config);
}
