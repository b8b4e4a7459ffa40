package io.robomw.cli;

import io.robomw.api.RobotException;
import io.robomw.console.Console;

import java.io.IOException;
import java.io.PrintWriter;
import java.util.concurrent.CountDownLatch;

/** Runs a console (page, recording or both) until Ctrl-C or SIGTERM, then finishes the recording. */
final class Waiting {

    private Waiting() {
    }

    static int runUntilStopped(Console.Builder builder, PrintWriter out, PrintWriter err, String command) throws InterruptedException {
        Console console;
        try {
            console = builder.start();
        } catch (IOException | IllegalArgumentException | IllegalStateException | RobotException e) {
            err.println(command + ": " + e.getMessage());
            err.flush();
            return 2;
        }
        console.pageAddress().ifPresent(a -> out.println("console at " + a));
        console.foxgloveAddress().ifPresent(a -> out.println("foxglove at " + a));
        console.recording().ifPresent(f -> out.println("recording to " + f + " (Ctrl-C ends it)"));
        out.flush();
        CountDownLatch stopped = new CountDownLatch(1);
        Thread closer = new Thread(() -> {
            console.close();
            stopped.countDown();
        }, command.replace(' ', '-') + "-shutdown");
        Runtime.getRuntime().addShutdownHook(closer);
        stopped.await();
        return 0;
    }
}
