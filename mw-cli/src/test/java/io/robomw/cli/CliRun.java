package io.robomw.cli;

import picocli.CommandLine;

import java.io.PrintWriter;
import java.io.StringWriter;
import java.time.Duration;

/**
 * One {@code mw} command run in this JVM, through {@link Mw#commandLine()} as the launcher runs
 * it (its converters and error handlers): exit status, standard output and standard error.
 *
 * @param status the exit status
 * @param out    what it printed on standard output
 * @param err    what it printed on standard error
 */
record CliRun(int status, String out, String err) {

    static CliRun mw(String... args) {
        return mw(Mw.commandLine(), args);
    }

    /**
     * A command that looks for a file that is not there: it waits {@code filePatience} for it (the launcher 30 s) before it
     * says the file is missing.
     */
    static CliRun mwWaitingForFiles(Duration filePatience, String... args) {
        return mw(Mw.commandLine(filePatience), args);
    }

    private static CliRun mw(CommandLine cl, String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        cl.setOut(new PrintWriter(out, true));
        cl.setErr(new PrintWriter(err, true));
        int status = cl.execute(args);
        return new CliRun(status, out.toString(), err.toString());
    }

    /** @return standard error's lines, without empty ones */
    java.util.List<String> errLines() {
        return err.lines().filter(l -> !l.isBlank()).toList();
    }
}
