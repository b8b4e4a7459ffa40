package io.robomw.cli;

import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Option;
import picocli.CommandLine.ScopeType;

import java.io.PrintWriter;

/**
 * The {@code mw} command: one launcher for everything a RoboMW user runs by hand. Each subcommand
 * is its own class; add new ones to the list below.
 *
 * <p>An error a command does not handle itself is one line on standard error,
 * {@code mw COMMAND: what went wrong}, and exit status 2; {@code --verbose} (on any command) adds
 * its stack trace.
 */
@Command(name = "mw", mixinStandardHelpOptions = true, version = "RoboMW 0.1.0",
        description = "RoboMW: one Java API over many robots.",
        subcommands = {DescribeCommand.class, SimCommand.class, EmulateCommand.class, MsgCommand.class, BrokerCommand.class, HostCommand.class,
                AgentsCommand.class, DispatchCommand.class, RetractCommand.class, DisposeCommand.class, DemoCommand.class, ConsoleCommand.class,
                RecordCommand.class, ReplayCommand.class, CommandLine.HelpCommand.class})
public final class Mw {

    /** RMI's keep-alive of idle connection threads, in milliseconds (read once, when RMI's transport loads). */
    static final String RMI_THREAD_KEEP_ALIVE = "sun.rmi.transport.tcp.threadKeepAliveTime";

    @Option(names = "--verbose", scope = ScopeType.INHERIT, description = "on an error, also show its stack trace")
    boolean verbose;

    /**
     * @param args the command line
     */
    public static void main(String[] args) {
        // RMI keeps a thread per idle connection for a minute by default: a host that served a burst
        // of agents would hold hundreds. 10 s is enough to reuse a connection between hops.
        if (System.getProperty(RMI_THREAD_KEEP_ALIVE) == null) {
            System.setProperty(RMI_THREAD_KEEP_ALIVE, "10000");
        }
        System.exit(commandLine().execute(args));
    }

    /** @return the {@code mw} command line, with its error handling: one line per error, the trace with --verbose */
    static CommandLine commandLine() {
        Mw mw = new Mw();
        CommandLine cl = new CommandLine(mw);
        cl.setExecutionExceptionHandler((e, command, parsed) -> {
            PrintWriter err = command.getErr();
            err.println(command.getCommandSpec().qualifiedName() + ": " + oneLine(e));
            if (mw.verbose) {
                e.printStackTrace(err);
            } else {
                err.println("(--verbose shows the stack trace)");
            }
            err.flush();
            return 2;
        });
        return cl;
    }

    /** @return whether --verbose was given (for a command that prints remote failures) */
    static boolean verbose(picocli.CommandLine.Model.CommandSpec spec) {
        return spec.root().userObject() instanceof Mw mw && mw.verbose;
    }

    /** @return an error's message, or its type when it has none, without the "java.lang." noise */
    static String oneLine(Throwable e) {
        String m = e.getMessage();
        if (m == null || m.isBlank()) {
            return e.getClass().getSimpleName();
        }
        int nl = m.indexOf('\n');
        return nl < 0 ? m : m.substring(0, nl);
    }
}
