package io.robomw.cli;

import io.robomw.console.Console;
import io.robomw.console.foxglove.FoxgloveServer;
import picocli.CommandLine.Option;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * {@code --foxglove [PORT]} on {@code mw sim}, {@code mw host}, {@code mw demo}, {@code mw console}
 * and {@code mw replay}: the run, live, as a Foxglove WebSocket on 127.0.0.1 (the recordings'
 * channels; Foxglove's teleop panel may drive the robots). Without a port, Foxglove's usual one,
 * {@value FoxgloveServer#DEFAULT_PORT}. Another address ({@code --foxglove-bind}) needs an access
 * token, from a file ({@code --foxglove-token-file}) or the environment
 * ({@value FoxgloveServer#TOKEN_ENV}), never from an option's value; as the rosbridge does.
 */
final class FoxgloveOption {

    /** Where the WebSocket listens by default: this machine only (reach it from elsewhere through an SSH tunnel, or give a token). */
    static final String BIND = "127.0.0.1";

    @Option(names = "--foxglove", arity = "0..1", paramLabel = "PORT", fallbackValue = "" + FoxgloveServer.DEFAULT_PORT,
            description = "also serve the run live to Foxglove (Open connection, Foxglove WebSocket, ws://127.0.0.1:PORT; default port "
                    + FoxgloveServer.DEFAULT_PORT + ", 0 picks a free one); its teleop panel can drive the robots")
    Integer port;

    @Option(names = "--foxglove-bind", paramLabel = "ADDRESS", defaultValue = BIND,
            description = "where the Foxglove WebSocket listens (default ${DEFAULT-VALUE}: this machine only; another address needs "
                    + "--foxglove-token-file or " + FoxgloveServer.TOKEN_ENV + ")")
    String bind = BIND;

    @Option(names = "--foxglove-token-file", paramLabel = "FILE",
            description = "file holding the access token Foxglove clients must give (ws://HOST:PORT/?token=TOKEN); default: the "
                    + FoxgloveServer.TOKEN_ENV + " environment variable, else none")
    Path tokenFile;

    boolean on() {
        return port != null;
    }

    /**
     * @param b a console to start
     * @return the same, serving Foxglove if asked
     * @throws IllegalArgumentException if the address is beyond this machine without a token, or the token file cannot be read
     */
    Console.Builder apply(Console.Builder b) {
        return port == null ? b : b.foxglove(bind, port, token());
    }

    /**
     * @param name the server's name
     * @return options to serve a replay with
     */
    FoxgloveServer.Options replay(String name) {
        return FoxgloveServer.Options.replay(name, BIND, port).listening(bind, token());
    }

    /** @return the token: the file's first line, else the environment's, else {@code null} */
    String token() {
        if (tokenFile != null) {
            try {
                String t = Files.readString(tokenFile, StandardCharsets.UTF_8).lines().findFirst().orElse("").strip();
                if (t.isEmpty()) {
                    throw new IllegalArgumentException("the Foxglove token file " + tokenFile + " is empty");
                }
                return t;
            } catch (IOException e) {
                throw new UncheckedIOException("cannot read the Foxglove token file " + tokenFile + ": " + e.getMessage(), e);
            }
        }
        String env = System.getenv(FoxgloveServer.TOKEN_ENV);
        return env == null || env.isBlank() ? null : env.strip();
    }
}
