/**
 * The communication component and the agency every robot has (the paper's Instruction Layer
 * links motion, perception, communication and agency): {@link io.robomw.agents.components.RobotMessaging}
 * and {@link io.robomw.agents.components.RobotAgency}, offered to the Configuration Layer through
 * the SPI in {@code io.robomw.api.spi} ({@code MessagingProvider}, {@code AgencyProvider}).
 */
package io.robomw.agents.components;
