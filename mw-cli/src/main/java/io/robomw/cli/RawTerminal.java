package io.robomw.cli;

import java.io.File;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.util.concurrent.TimeUnit;

/**
 * The controlling terminal in "one key at a time" mode for {@code mw robot teleop}: no line
 * buffering, no echo, Ctrl-C delivered as a key (so the robot is stopped before the command
 * ends). Set and restored with {@code stty} on {@code /dev/tty} (POSIX); closing restores the
 * settings it found.
 */
final class RawTerminal implements AutoCloseable {

    private static final File TTY = new File("/dev/tty");

    private final String saved;

    private RawTerminal(String saved) {
        this.saved = saved;
    }

    /**
     * @return the terminal, switched to reading single keys
     * @throws IOException if there is no terminal (input redirected, no /dev/tty, no stty)
     */
    static RawTerminal enter() throws IOException {
        if (System.console() == null || !TTY.exists()) {
            throw new IOException("teleop reads single keys and needs a terminal; there is none");
        }
        String saved = stty("-g").strip();
        stty("-icanon", "-echo", "-isig", "min", "1", "time", "0");
        return new RawTerminal(saved);
    }

    private static String stty(String... args) throws IOException {
        String[] command = new String[args.length + 1];
        command[0] = "stty";
        System.arraycopy(args, 0, command, 1, args.length);
        Process p = new ProcessBuilder(command).redirectInput(TTY).redirectError(ProcessBuilder.Redirect.INHERIT).start();
        try {
            String out = new String(p.getInputStream().readAllBytes(), StandardCharsets.US_ASCII);
            if (!p.waitFor(5, TimeUnit.SECONDS) || p.exitValue() != 0) {
                throw new IOException("stty " + String.join(" ", args) + " failed: the terminal cannot be set to read single keys");
            }
            return out;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while setting the terminal", e);
        }
    }

    @Override
    public void close() throws IOException {
        stty(saved);
    }
}
