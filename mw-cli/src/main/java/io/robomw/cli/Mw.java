package io.robomw.cli;

import picocli.CommandLine;
import picocli.CommandLine.Command;

/**
 * The {@code mw} command: one launcher for everything a RoboMW user runs by hand. Each subcommand
 * is its own class; add new ones to the list below.
 */
@Command(name = "mw", mixinStandardHelpOptions = true, version = "RoboMW 0.1.0",
        description = "RoboMW: one Java API over many robots.",
        subcommands = {DescribeCommand.class, SimCommand.class, EmulateCommand.class, MsgCommand.class, BrokerCommand.class, HostCommand.class,
                AgentsCommand.class, DispatchCommand.class, DemoCommand.class, ConsoleCommand.class, RecordCommand.class, ReplayCommand.class,
                CommandLine.HelpCommand.class})
public final class Mw {

    /**
     * @param args the command line
     */
    public static void main(String[] args) {
        System.exit(new CommandLine(new Mw()).execute(args));
    }
}
