package io.robomw.cli;

import io.robomw.console.Console;
import io.robomw.console.foxglove.FoxgloveServer;
import io.robomw.console.foxglove.Teleop;
import io.robomw.console.mcap.McapFormatException;
import io.robomw.console.observe.Observer;
import io.robomw.console.record.McapReplay;
import io.robomw.console.record.ReplayPicture;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.Locale;
import java.util.concurrent.Callable;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.atomic.AtomicBoolean;

/**
 * {@code mw replay FILE.mcap}: plays a recording into the console's page (and, with {@code --png},
 * into a picture; with {@code --foxglove}, to Foxglove live, in recorded time), at the recorded
 * pace times {@code --speed}. Without {@code --png} the page stays up after the replay until
 * Ctrl-C; with {@code --png} the command draws the picture and exits, as a command that writes a
 * file does, unless {@code --console} asks for the page too. {@code --no-console} with
 * {@code --foxglove} serves Foxglove only (until Ctrl-C).
 */
@Command(name = "replay", mixinStandardHelpOptions = true,
        description = {"Plays an MCAP recording (mw record, --record) back into the console's page and/or a PNG.",
                "Example: mw replay run.mcap --speed 4 --png run.png"})
final class ReplayCommand implements Callable<Integer> {

    @Parameters(index = "0", paramLabel = "FILE.mcap", description = "the recording")
    Path file;

    @Option(names = "--speed", defaultValue = "1", description = "recorded seconds per second (default ${DEFAULT-VALUE}); 0 = as fast as possible")
    double speed;

    @Option(names = "--png", paramLabel = "FILE", description = "draw the replayed trajectories into this PNG at the end")
    Path png;

    @Option(names = "--width", defaultValue = "1000", description = "width of the PNG, pixels (default ${DEFAULT-VALUE})")
    int width;

    @Option(names = "--no-console", description = "no page: only the picture or Foxglove (needs --png or --foxglove); the default with --png")
    boolean noConsole;

    @Option(names = "--console", description = "with --png: show the replay in the page too, kept up until Ctrl-C (without --png the page is the default)")
    boolean withConsole;

    @picocli.CommandLine.Mixin
    FoxgloveOption foxglove;

    @Option(names = "--bind", defaultValue = "127.0.0.1", description = "address the page listens on (default ${DEFAULT-VALUE})")
    String bind;

    @Option(names = "--port", defaultValue = "8080", description = "the page's port (default ${DEFAULT-VALUE}, or a free one when it is taken; 0 picks a free one)")
    int port;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (!(speed >= 0) || Double.isInfinite(speed)) {
            throw new CommandLine.ParameterException(spec.commandLine(), "--speed must be a number >= 0, got " + speed);
        }
        if (noConsole && png == null && !foxglove.on()) {
            throw new CommandLine.ParameterException(spec.commandLine(), "--no-console leaves nothing to show: add --png FILE or --foxglove");
        }
        if (noConsole && withConsole) {
            throw new CommandLine.ParameterException(spec.commandLine(), "--console and --no-console contradict each other; give one");
        }
        // The page when asked for, or when nothing else shows the replay: --png alone writes its file and exits.
        boolean page = withConsole || (!noConsole && png == null);
        ReplayPicture picture = new ReplayPicture();
        Console console = null;
        FoxgloveServer live = null;
        AtomicBoolean stop = new AtomicBoolean();
        CountDownLatch interrupted = new CountDownLatch(1);
        CountDownLatch stopped = new CountDownLatch(1);
        Thread hook = new Thread(() -> {
            stop.set(true);
            interrupted.countDown();
            try {
                stopped.await();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }, "mw-replay-shutdown");
        Runtime.getRuntime().addShutdownHook(hook);
        try {
            if (page) {
                console = Console.builder("mw replay " + file + (speed == 1 ? "" : " at " + speed + "x")).page(bind, PagePort.choose(bind, port, spec.commandLine().getParseResult().hasMatchedOption("--port"), err, "mw replay")).start();
                out.println("console at " + console.pageAddress().orElseThrow());
                out.flush();
            }
            if (foxglove.on()) {
                // Foxglove is told the recorded times (and the replay's time, the time capability); the page ages what it shows on the replay's clock.
                try {
                    live = FoxgloveServer.create(foxglove.replay("mw replay " + file));
                    live.start(Teleop.NONE);
                } catch (IOException | RuntimeException e) {
                    err.println("mw replay: " + e.getMessage());
                    return 2;
                }
                out.println("foxglove at " + live.address());
                out.flush();
            }
            Observer sink = console == null ? picture : Observer.all(console.observer(), picture);
            McapReplay.Played played;
            try {
                played = McapReplay.play(file, sink, live == null ? o -> { } : live, speed, stop::get);
            } catch (McapFormatException e) {
                err.println("mw replay: " + e.getMessage());
                return 2;
            } catch (java.nio.file.NoSuchFileException e) {
                err.println("mw replay: there is no file " + file);
                return 2;
            } catch (IOException e) {
                err.println("mw replay: cannot replay " + file + ": " + e.getMessage());
                return 2;
            }
            out.printf(Locale.ROOT, "replayed %d messages (%.1f s recorded)%s%n", played.messages(), played.recordedSeconds(),
                    played.truncated() ? "; the file ends early (its recorder was killed?): played up to there" : "");
            if (png != null) {
                picture.write(png, width);
                out.println("wrote " + png);
            }
            out.flush();
            if ((console != null || live != null) && !stop.get()) {
                out.println((console != null ? "the console keeps" : "Foxglove keeps") + " showing the replay until Ctrl-C");
                out.flush();
                interrupted.await();
            }
            return 0;
        } finally {
            if (console != null) {
                console.close();
            }
            if (live != null) {
                live.close();
            }
            stopped.countDown();
            try {
                Runtime.getRuntime().removeShutdownHook(hook);
            } catch (IllegalStateException e) {
                // shutting down already
            }
        }
    }
}
