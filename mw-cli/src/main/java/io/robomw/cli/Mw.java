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
        boundRmiConnections();
        System.exit(new CommandLine(new Mw()).execute(args));
    }

    /**
     * Java RMI's own defaults, set before RMI starts unless the user set them: an RMI connection
     * that sends no call for 2 minutes is closed (the JDK waits 2 hours, so held connections pile
     * up), and a thread that served a closed connection ends after 5 s idle (the JDK keeps it a
     * minute). Agent hosts and RMI messaging endpoints serve peers they do not know yet.
     */
    static void boundRmiConnections() {
        setIfAbsent("sun.rmi.transport.tcp.readTimeout", "120000");
        setIfAbsent("sun.rmi.transport.tcp.threadKeepAliveTime", "5000");
    }

    private static void setIfAbsent(String property, String value) {
        if (System.getProperty(property) == null) {
            System.setProperty(property, value);
        }
    }
}
