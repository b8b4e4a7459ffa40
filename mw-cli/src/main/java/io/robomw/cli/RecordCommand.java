package io.robomw.cli;

import io.robomw.console.Console;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.nio.file.Path;
import java.util.concurrent.Callable;

/** {@code mw record FILE.mcap}: records agent hosts and served robots into an MCAP file until Ctrl-C. */
@Command(name = "record", mixinStandardHelpOptions = true,
        description = {"Records agent hosts (agents, itineraries, events) and served robots (poses, sensors) into an MCAP file that Foxglove opens.",
                "Example: mw record run.mcap --host rmi://127.0.0.1:1099/nxt --robot tcp://127.0.0.1:7000/nxt --key-file cluster.key"})
final class RecordCommand implements Callable<Integer> {

    @Parameters(index = "0", paramLabel = "FILE.mcap", description = "the recording (replaced if it exists)")
    Path file;

    @Mixin
    ConsoleCommand.WatchOptions watch;

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws Exception {
        Console.Builder b = watch.apply(Console.builder("mw " + String.join(" ", spec.commandLine().getParseResult().originalArgs())))
                .noPage().record(file);
        return Waiting.runUntilStopped(b, spec.commandLine().getOut(), spec.commandLine().getErr(), "mw record");
    }
}
