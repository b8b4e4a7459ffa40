package io.robomw.sim.emulator;

import java.io.IOException;

/**
 * A virtual robot bound to a robot of a simulated world, serving its firmware's protocol to the
 * real driver: a brick on a pseudo-terminal or TCP ({@link BrickEmulator}), or the Aibo's URBI
 * server on TCP ({@link io.robomw.sim.emulator.aibo.AiboEmulator}). Closing it stops serving; at the
 * next world step its robot stops and it unbinds from the simulation.
 */
public interface Emulator extends AutoCloseable {

    /**
     * Creates a pseudo-terminal and serves on it.
     *
     * @return the device path a driver opens, for example {@code /dev/pts/5}
     * @throws IOException if no pseudo-terminal can be made, or the robot's protocol does not
     *                     run over a serial line
     */
    String startOnPseudoTerminal() throws IOException;

    /**
     * Serves on a TCP port.
     *
     * @param bindAddress the address to listen on (127.0.0.1 for tests)
     * @param port        the port, 0 for any free one
     * @return the port it listens on
     * @throws IOException if it cannot listen
     */
    int startOnTcp(String bindAddress, int port) throws IOException;

    /** @return where it serves, for messages */
    String describe();

    /** Stops serving; the robot stops at the next world step. */
    @Override
    void close();
}
