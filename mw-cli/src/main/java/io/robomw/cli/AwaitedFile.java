package io.robomw.cli;

import picocli.CommandLine.Model.CommandSpec;

import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.locks.LockSupport;

/**
 * A file a command needs and that another command may still be writing: {@code mw emulate
 * --write-robot nxt.yaml &} started a moment ago, then {@code mw describe nxt.yaml} pasted right
 * after it. The command waits for the file a bounded time, saying once what it waits for, as
 * {@code ros2 launch} users expect of a consumer started with its producer; a file that does not
 * come is then reported as missing, as before.
 */
final class AwaitedFile {

    /** How long a command waits for a file that is not there yet. */
    static final Duration PATIENCE = Duration.ofSeconds(30);
    private static final long LOOK_EVERY_NANOS = 100_000_000L;

    private AwaitedFile() {
    }

    /**
     * @param file    the file
     * @param spec    the command waiting: its standard error says that it waits; its root, for how long ({@link Mw#filePatience})
     * @param command the command, for that line
     * @return whether the file is there (at once, or within {@link #PATIENCE})
     */
    static boolean await(Path file, CommandSpec spec, String command) {
        if (Files.exists(file)) {
            return true;
        }
        Duration patience = Mw.filePatience(spec);
        PrintWriter err = spec.commandLine().getErr();
        err.println(command + ": waiting up to " + Durations.format(patience) + " for " + file + " (a command started just before, such as"
                + " mw emulate --write-robot, may still be writing it)");
        err.flush();
        long deadline = System.nanoTime() + patience.toNanos();
        while (!Files.exists(file) && System.nanoTime() - deadline < 0) {
            LockSupport.parkNanos(LOOK_EVERY_NANOS); // a file appearing: polled, as there is nothing to be woken by
            if (Thread.currentThread().isInterrupted()) {
                return false;
            }
        }
        return Files.exists(file);
    }
}
