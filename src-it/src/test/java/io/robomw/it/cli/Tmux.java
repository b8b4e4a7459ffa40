package io.robomw.it.cli;

import io.robomw.testkit.Await;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * A terminal for keyboard tests: a detached tmux session on a server of its own (its own socket,
 * so a user's tmux is untouched) running bash, into which a test types keys and whose screen it
 * reads. Closing it kills that server and everything running in it.
 */
final class Tmux implements AutoCloseable {

    /** How often the screen is read while waiting (each read is a process). */
    private static final long READ_EVERY_NANOS = 100_000_000L;

    private final String socket;
    private final String session = "t";
    private long lastRead;
    private String lastScreen = "";

    Tmux(String socket) throws IOException, InterruptedException {
        this.socket = socket;
        tmux("new-session", "-d", "-s", session, "-x", "160", "-y", "50", "bash --norc --noprofile");
    }

    /** Types a line into the shell and presses Enter. */
    void typeLine(String line) throws IOException, InterruptedException {
        tmux("send-keys", "-t", session, "-l", line);
        tmux("send-keys", "-t", session, "Enter");
    }

    /** Presses one key (a character, sent literally). */
    void press(String key) throws IOException, InterruptedException {
        tmux("send-keys", "-t", session, "-l", key);
    }

    /** Presses Ctrl-C: the terminal sends SIGINT to its foreground process group. */
    void ctrlC() throws IOException, InterruptedException {
        tmux("send-keys", "-t", session, "C-c");
    }

    /** @return the screen and its scroll-back */
    String screen() throws IOException, InterruptedException {
        return tmux("capture-pane", "-p", "-t", session, "-S", "-200");
    }

    /** Waits until the screen shows {@code text}. */
    void awaitScreen(String text, Duration within) {
        Await.until("the terminal shows '" + text + "'; it shows:\n" + lastScreen, within, () -> {
            long now = System.nanoTime();
            if (now - lastRead < READ_EVERY_NANOS) {
                return false;
            }
            lastRead = now;
            try {
                lastScreen = screen();
            } catch (IOException e) {
                throw new IllegalStateException(e);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new IllegalStateException(e);
            }
            return lastScreen.contains(text);
        });
    }

    private String tmux(String... args) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>(List.of("tmux", "-L", socket, "-f", "/dev/null"));
        command.addAll(List.of(args));
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        String out = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        if (!p.waitFor(10, TimeUnit.SECONDS) || p.exitValue() != 0) {
            throw new IOException(String.join(" ", command) + " failed: " + out);
        }
        return out;
    }

    @Override
    public void close() throws IOException, InterruptedException {
        Process p = new ProcessBuilder("tmux", "-L", socket, "kill-server").redirectErrorStream(true).start();
        p.getInputStream().readAllBytes();
        p.waitFor(10, TimeUnit.SECONDS);
    }
}
