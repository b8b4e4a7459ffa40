/**
 * The transport SPI: how a messaging node moves frames over one kind of address. A transport is
 * found through {@link java.util.ServiceLoader} by its scheme ({@link TransportProvider}); to add
 * one, implement {@link TransportProvider} and {@link Transport} and list the provider in
 * {@code META-INF/services/io.robomw.agents.messaging.spi.TransportProvider}. Nothing else changes:
 * frames, security, topics and replies are the node's business, not the transport's.
 */
package io.robomw.agents.messaging.spi;
