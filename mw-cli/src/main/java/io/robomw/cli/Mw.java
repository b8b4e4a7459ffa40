package io.robomw.cli;

import picocli.AutoComplete;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Option;
import picocli.CommandLine.ScopeType;

import java.io.PrintWriter;
import java.time.Duration;
import java.util.Arrays;

/**
 * The {@code mw} command: one launcher for everything a RoboMW user runs by hand. Each subcommand
 * is its own class; add new ones to the list below.
 *
 * <p>What every command shares: {@code --help} (and {@code -h}), whatever else is missing;
 * durations read by {@link Durations} ({@code 30}, {@code 500ms}, {@code 2m}, ISO-8601); a usage
 * error is one line on standard error, {@code mw COMMAND: what is wrong (mw COMMAND --help)}, and
 * exit status 2; an error a command does not handle itself is one line,
 * {@code mw COMMAND: what went wrong}, and exit status 2; {@code --verbose} (on any command) adds
 * its stack trace.
 */
@Command(name = "mw", mixinStandardHelpOptions = true, version = "RoboMW 0.1.0",
        description = "RoboMW: one Java API over many robots.",
        subcommands = {DescribeCommand.class, SimCommand.class, EmulateCommand.class, MsgCommand.class, BrokerCommand.class, HostCommand.class,
                AgentsCommand.class, DispatchCommand.class, RetractCommand.class, DisposeCommand.class, DemoCommand.class, ConsoleCommand.class, RecordCommand.class, ReplayCommand.class,
                RunCommand.class, ClasspathCommand.class, RobotCommand.class, NewCommand.class, UpCommand.class, NodesCommand.class, TopicsCommand.class,
                RosbridgeCommand.class,
                CommandLine.HelpCommand.class, AutoComplete.GenerateCompletion.class})
public final class Mw {

    /** Exit status of a usage error or any other error a command did not handle itself. */
    static final int USER_ERROR = 2;


    @Option(names = "--verbose", scope = ScopeType.INHERIT, description = "on an error, also show its stack trace")
    boolean verbose;

    /** How long a command waits for a file that is not there yet ({@link AwaitedFile}); tests of a missing file shorten it. */
    private final Duration filePatience;

    private Mw(Duration filePatience) {
        this.filePatience = filePatience;
    }

    /**
     * @param args the command line
     */
    public static void main(String[] args) {
        boundRmiConnections();
        System.exit(commandLine().execute(args));
    }

    /** @return the {@code mw} command line, with its error handling: one line per error, the trace with --verbose */
    static CommandLine commandLine() {
        return commandLine(AwaitedFile.PATIENCE);
    }

    /**
     * @param filePatience how long a command waits for a file that is not there yet (a test seam: the launcher waits
     *                     {@link AwaitedFile#PATIENCE})
     * @return the {@code mw} command line
     */
    static CommandLine commandLine(Duration filePatience) {
        Mw mw = new Mw(filePatience);
        CommandLine cl = new CommandLine(mw);
        cl.registerConverter(Duration.class, new Durations());
        cl.setParameterExceptionHandler((e, args) -> {
            CommandLine failed = e.getCommandLine();
            PrintWriter err = failed.getErr();
            String name = failed.getCommandSpec().qualifiedName();
            StringBuilder line = new StringBuilder(name).append(": ").append(oneLine(e));
            if (e instanceof CommandLine.UnmatchedArgumentException u && !u.getSuggestions().isEmpty()) {
                line.append("; did you mean ").append(String.join(" or ", u.getSuggestions())).append('?');
            }
            line.append(" (").append(name).append(" --help)");
            err.println(line);
            if (Arrays.asList(args).contains("--verbose")) {
                e.printStackTrace(err);
            }
            err.flush();
            return USER_ERROR;
        });
        cl.setExecutionExceptionHandler((e, command, parsed) -> {
            PrintWriter err = command.getErr();
            boolean trace = mw.verbose || parsed.originalArgs().contains("--verbose");
            err.println(command.getCommandSpec().qualifiedName() + ": " + oneLine(e) + (trace ? "" : " (--verbose shows the stack trace)"));
            if (trace) {
                e.printStackTrace(err);
            }
            err.flush();
            return USER_ERROR;
        });
        // Everything after the program is the program's, options too.
        cl.getSubcommands().get("run").setStopAtPositional(true);
        // The completion script completes "mw" (put the launcher on the PATH, or alias it).
        cl.getSubcommands().get("generate-completion").getCommandSpec().usageMessage().hidden(false)
                .description("Print a bash/zsh completion script for mw: source <(mw generate-completion)");
        return cl;
    }

    /** @return whether --verbose was given (for a command that prints remote failures) */
    static boolean verbose(CommandLine.Model.CommandSpec spec) {
        return spec.root().userObject() instanceof Mw mw && mw.verbose;
    }

    /** @return how long the command of {@code spec} waits for a file that is not there yet */
    static Duration filePatience(CommandLine.Model.CommandSpec spec) {
        return spec.root().userObject() instanceof Mw mw ? mw.filePatience : AwaitedFile.PATIENCE;
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

    /**
     * Java RMI's own defaults, set before RMI starts unless the user set them: an RMI connection
     * that sends no call for 2 minutes is closed (the JDK waits 2 hours, so held connections pile
     * up), and a thread that served a closed connection ends after 5 s idle (the JDK keeps it a
     * minute). Agent hosts and RMI messaging endpoints serve peers they do not know yet.
     */
    static void boundRmiConnections() {
        setIfAbsent("sun.rmi.transport.tcp.readTimeout", "120000");
        // RMI keeps a thread per idle connection for a minute by default: a host that served a burst
        // of agents, or a peer's 300 connections, would hold hundreds. 5 s is plenty to reuse a
        // connection between hops (milliseconds apart).
        setIfAbsent("sun.rmi.transport.tcp.threadKeepAliveTime", "5000");
    }

    private static void setIfAbsent(String property, String value) {
        if (System.getProperty(property) == null) {
            System.setProperty(property, value);
        }
    }
}
