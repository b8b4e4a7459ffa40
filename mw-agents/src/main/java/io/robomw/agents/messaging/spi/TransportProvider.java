package io.robomw.agents.messaging.spi;

/** Makes transports for one address scheme; found through {@link java.util.ServiceLoader}. */
public interface TransportProvider {

    /** @return the scheme, for example {@code tcp} */
    String scheme();

    /**
     * @param context the node the transport works for
     * @return a transport for that node; the node closes it
     */
    Transport create(TransportContext context);
}
