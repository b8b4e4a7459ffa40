/**
 * Byte links from the Platform Layer to bricks, and the communicator drivers use over them.
 *
 * <ul>
 *   <li>{@link io.robomw.platform.link.Link}: one byte stream with timed reads;
 *       {@link io.robomw.platform.link.SerialLink} (jSerialComm, by device path),
 *       {@link io.robomw.platform.link.TcpClientLink} and
 *       {@link io.robomw.platform.link.TcpServerLink}.</li>
 *   <li>{@link io.robomw.platform.link.Communicator}: sends, receives with deadlines, reads
 *       length-driven frames whole, reopens, and writes a {@link io.robomw.platform.link.WireLog};
 *       whether a brick's link is up is kept in one place, its link agent
 *       ({@code io.robomw.platform.brick.LinkAgent}).</li>
 *   <li>{@link io.robomw.platform.link.PseudoTerminal}: an in-process pty pair, so an emulator can
 *       stand in for a serial brick with nothing installed.</li>
 * </ul>
 *
 * A peer that goes away is a {@link io.robomw.platform.link.LinkLostException}; bytes that do not
 * come in time are a {@link io.robomw.platform.link.LinkTimeoutException}. Both are
 * {@link java.io.IOException}s whose message starts with the link's
 * {@link io.robomw.platform.link.Link#describe() description}.
 */
package io.robomw.platform.link;
