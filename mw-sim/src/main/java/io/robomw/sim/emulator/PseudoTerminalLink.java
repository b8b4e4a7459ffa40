package io.robomw.sim.emulator;

import io.robomw.platform.link.Link;
import io.robomw.platform.link.PseudoTerminal;

import java.io.IOException;
import java.time.Duration;

/** The master side of a pseudo-terminal as a {@link Link}: what a brick emulator serves on. */
final class PseudoTerminalLink implements Link {

    private final PseudoTerminal pty;
    private volatile boolean closed;

    PseudoTerminalLink(PseudoTerminal pty) {
        this.pty = pty;
    }

    @Override
    public void open() {
    }

    @Override
    public boolean isOpen() {
        return !closed;
    }

    @Override
    public void write(byte[] data, int off, int len) throws IOException {
        pty.masterOutput().write(data, off, len);
        pty.masterOutput().flush();
    }

    @Override
    public int read(byte[] buf, int off, int len, Duration timeout) throws IOException {
        return pty.read(buf, off, len, timeout);
    }

    @Override
    public String describe() {
        return "pseudo-terminal " + pty.devicePath();
    }

    @Override
    public void close() {
        closed = true;
        pty.close();
    }
}
