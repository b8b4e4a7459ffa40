package io.robomw.cli;

import io.robomw.console.Console;
import io.robomw.console.foxglove.FoxgloveServer;
import picocli.CommandLine.Option;

/**
 * {@code --foxglove [PORT]} on {@code mw sim}, {@code mw host}, {@code mw demo}, {@code mw console}
 * and {@code mw replay}: the run, live, as a Foxglove WebSocket on 127.0.0.1 (the recordings'
 * channels; Foxglove's teleop panel may drive the robots). Without a port, Foxglove's usual one,
 * {@value FoxgloveServer#DEFAULT_PORT}.
 */
final class FoxgloveOption {

    /** Where the WebSocket listens: this machine only (reach it from elsewhere through an SSH tunnel). */
    static final String BIND = "127.0.0.1";

    @Option(names = "--foxglove", arity = "0..1", paramLabel = "PORT", fallbackValue = "" + FoxgloveServer.DEFAULT_PORT,
            description = "also serve the run live to Foxglove (Open connection, Foxglove WebSocket, ws://127.0.0.1:PORT; default port "
                    + FoxgloveServer.DEFAULT_PORT + ", 0 picks a free one); its teleop panel can drive the robots")
    Integer port;

    boolean on() {
        return port != null;
    }

    /** @param b a console to start @return the same, serving Foxglove if asked */
    Console.Builder apply(Console.Builder b) {
        return port == null ? b : b.foxglove(BIND, port);
    }
}
