package io.robomw.cli;

import org.junit.jupiter.api.Test;
import picocli.CommandLine;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** What every {@code mw} command shares: --help, durations, one-line user errors with exit 2, completion. */
class CommandLineTest {

    /** @return every command's path below mw: [describe], [msg], [msg, pub], ... */
    private static List<List<String>> commands(CommandLine cl, List<String> path) {
        List<List<String>> all = new ArrayList<>();
        for (var e : cl.getSubcommands().entrySet()) {
            List<String> p = new ArrayList<>(path);
            p.add(e.getKey());
            all.add(p);
            all.addAll(commands(e.getValue(), p));
        }
        return all;
    }

    @Test
    void helpWorksOnEveryCommandAndSubcommandWhateverElseIsMissing() {
        List<List<String>> all = commands(Mw.commandLine(), List.of());
        assertTrue(all.size() >= 15, "the commands: " + all);
        assertTrue(all.contains(List.of("describe")) && all.contains(List.of("emulate")) && all.contains(List.of("msg", "pub")), all.toString());
        for (List<String> command : all) {
            List<String> args = new ArrayList<>(command);
            args.add("--help");
            CliRun run = CliRun.mw(args.toArray(String[]::new));
            assertEquals(0, run.status(), command + " --help: " + run.err());
            assertTrue(run.out().contains("Usage: mw " + String.join(" ", command)), command + " --help printed:\n" + run.out());
            assertTrue(run.out().contains("--verbose"), command + " --help lists --verbose:\n" + run.out());
        }
    }

    @Test
    void durationsAreReadTheSameWayEverywhere() {
        assertEquals(Duration.ofSeconds(30), Durations.parse("30"));
        assertEquals(Duration.ofSeconds(30), Durations.parse("30s"));
        assertEquals(Duration.ofMillis(500), Durations.parse("500ms"));
        assertEquals(Duration.ofMinutes(2), Durations.parse("2m"));
        assertEquals(Duration.ofHours(1), Durations.parse("1h"));
        assertEquals(Duration.ofMillis(1500), Durations.parse("1.5"));
        assertEquals(Duration.ofSeconds(30), Durations.parse("PT30S"));
        assertEquals(Duration.ofSeconds(90), Durations.parse("pt1m30s"));
        for (String bad : List.of("-1", "abc", "PTX", "30 parsecs", "")) {
            CommandLine.TypeConversionException e = assertThrows(CommandLine.TypeConversionException.class, () -> Durations.parse(bad), bad);
            assertTrue(e.getMessage().contains("500ms, 30s, 2m"), e.getMessage());
        }
        assertEquals("500ms", Durations.format(Duration.ofMillis(500)));
        assertEquals("2m", Durations.format(Duration.ofMinutes(2)));
        assertEquals("1.5s", Durations.format(Duration.ofMillis(1500)));

        // The same options take every form: dispatch's time-out (once ISO-8601 only) and msg's (once seconds only).
        CommandLine.ParseResult dispatch = Mw.commandLine().parseArgs("dispatch", "--jar", "a.jar", "--agent", "A", "--timeout", "30", "rmi://127.0.0.1:1/x");
        assertEquals(Duration.ofSeconds(30), dispatch.subcommand().matchedOptionValue("--timeout", null));
        CommandLine.ParseResult send = Mw.commandLine().parseArgs("msg", "send", "tcp://127.0.0.1:1", "x", "t", "hi", "--timeout", "PT2M");
        assertEquals(Duration.ofMinutes(2), send.subcommand().subcommand().matchedOptionValue("--timeout", null));
        CommandLine.ParseResult sim = Mw.commandLine().parseArgs("sim", "w.yaml", "--duration", "500ms");
        assertEquals(Duration.ofMillis(500), sim.subcommand().matchedOptionValue("--duration", null));
    }

    @Test
    void aUsageErrorIsOneLineWithTheFixAndExitTwo() {
        CliRun missing = CliRun.mw("describe");
        assertEquals(2, missing.status());
        assertEquals(1, missing.errLines().size(), missing.err());
        assertTrue(missing.err().startsWith("mw describe: Missing required parameter: 'FILE.yaml'"), missing.err());
        assertTrue(missing.err().contains("(mw describe --help)"), missing.err());

        CliRun badDuration = CliRun.mw("msg", "send", "tcp://127.0.0.1:1", "x", "t", "hi", "--timeout", "soon");
        assertEquals(2, badDuration.status());
        assertEquals(1, badDuration.errLines().size(), badDuration.err());
        assertTrue(badDuration.err().contains("'soon' is not a duration"), badDuration.err());

        CliRun typo = CliRun.mw("describ", "x.yaml");
        assertEquals(2, typo.status());
        assertTrue(typo.err().contains("did you mean describe"), typo.err());

        CliRun wire = CliRun.mw("host", "--name", "h", "--port", "0", "--no-messaging", "--no-wire", "--wire-port", "7001");
        assertEquals(2, wire.status());
        assertEquals(1, wire.errLines().size(), wire.err());
        assertTrue(wire.err().contains("--wire-port and --no-wire contradict each other"), wire.err());

        CliRun verbose = CliRun.mw("describe", "--verbose");
        assertEquals(2, verbose.status());
        assertTrue(verbose.err().contains("\tat picocli."), "--verbose adds the trace: " + verbose.err());
    }

    @Test
    void platformsAreSpelledAsRobotFilesSpellThem() {
        CliRun underscore = CliRun.mw("emulate", "ft_intelligent", "--world", "w.yaml", "--robot", "ft");
        assertEquals(2, underscore.status());
        assertEquals(1, underscore.errLines().size(), underscore.err());
        assertTrue(underscore.err().contains("did you mean 'ft-intelligent'?"), underscore.err());
        CommandLine.ParseResult dashed = Mw.commandLine().parseArgs("emulate", "ft-intelligent", "--world", "w.yaml", "--robot", "ft");
        assertEquals("ft-intelligent", dashed.subcommand().matchedPositionalValue(0, null).toString());
    }

    @Test
    void completionScriptCompletesEveryCommand() {
        CliRun run = CliRun.mw("generate-completion");
        assertEquals(0, run.status(), run.err());
        assertTrue(run.out().contains("complete -F _complete_mw"), run.out().lines().limit(5).toList().toString());
        assertTrue(run.out().contains("describe") && run.out().contains("emulate"), "the script knows the commands");
    }
}
