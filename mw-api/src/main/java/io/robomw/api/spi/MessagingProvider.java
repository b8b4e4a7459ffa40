package io.robomw.api.spi;

/**
 * Gives robots their communication component; found through {@link java.util.ServiceLoader}
 * ({@code META-INF/services/io.robomw.api.spi.MessagingProvider}). {@code mw-agents} provides
 * one; the Configuration Layer asks for it without compiling against it.
 */
public interface MessagingProvider {

    /**
     * Opens one robot's component. It may start at once or on first use, as the settings say.
     *
     * @param config the robot's messaging settings
     * @return the component
     * @throws io.robomw.api.MessagingException if it must start now and cannot (an address in use...)
     */
    MessagingComponent open(MessagingConfig config);
}
