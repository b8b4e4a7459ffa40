package io.robomw.it.docs;

import io.robomw.cli.ShellWords;
import io.robomw.it.StdoutLines;
import io.robomw.it.demo.MwProcess;

import java.io.File;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

/**
 * Runs the commands of a docs page as written, the way a user types them in one terminal: every
 * line of its {@code sh} blocks in order, in a scratch directory that has the checkout's
 * {@code examples} (so the page's paths are the checkout's) and where {@code ./mw} is the
 * distribution. A line ending in {@code &} runs in the background and the next line starts at once,
 * as when a person pastes the block (nobody waits for a background command's first line: the
 * commands after it must wait for what they need themselves); {@code kill %N} stops
 * the N-th of them; {@code cd DIR} changes the directory; {@code mvn} gets the test's options
 * first ({@link #maven}); any other line must exit 0. Everything still running at the end is
 * stopped. Only {@code sh} blocks run: a page shows one-time set-up in a {@code shell} block.
 */
final class DocCommands implements AutoCloseable {

    private static final Pattern SH_BLOCK = Pattern.compile("(?ms)^```sh\\n(.*?)^```");

    private final Path scratch;
    private final Path logs;
    private final List<String> classPath;
    private final List<String> mavenOptions = new ArrayList<>();
    private final List<Process> background = new ArrayList<>();
    private final List<String> backgroundNames = new ArrayList<>();
    private final List<StdoutLines> backgroundOutput = new ArrayList<>();
    private final List<String> transcript = new ArrayList<>();
    private Path dir;
    private int count;

    /**
     * @param scratch an empty directory to run in
     */
    DocCommands(Path scratch) throws IOException {
        this.scratch = scratch;
        this.dir = scratch;
        this.logs = Path.of("target", "it-logs");
        Files.createDirectories(logs);
        Files.createSymbolicLink(scratch.resolve("examples"), MwProcess.CHECKOUT.resolve("examples"));
        this.classPath = List.of(MwProcess.middlewareOnlyClassPath());
    }

    /**
     * @param options options every {@code mvn} line of the page gets first (the test's local repository, offline)
     * @return this
     */
    DocCommands maven(List<String> options) {
        mavenOptions.addAll(options);
        return this;
    }

    /** @return the commands of a page's {@code sh} blocks, in order, without comments and blank lines */
    static List<String> commands(Path page) throws IOException {
        List<String> commands = new ArrayList<>();
        Matcher m = SH_BLOCK.matcher(Files.readString(page, StandardCharsets.UTF_8));
        while (m.find()) {
            String pending = "";
            for (String raw : m.group(1).split("\n")) {
                String line = stripComment(raw).strip();
                if (line.endsWith("\\")) {
                    pending += line.substring(0, line.length() - 1) + " ";
                    continue;
                }
                line = (pending + line).strip();
                pending = "";
                if (!line.isEmpty()) {
                    commands.add(line);
                }
            }
        }
        return commands;
    }

    /** Drops a trailing "# ..." comment that is not inside quotes. */
    private static String stripComment(String line) {
        boolean single = false;
        boolean dbl = false;
        for (int i = 0; i < line.length(); i++) {
            char c = line.charAt(i);
            if (c == '\'' && !dbl) {
                single = !single;
            } else if (c == '"' && !single) {
                dbl = !dbl;
            } else if (c == '#' && !single && !dbl && (i == 0 || Character.isWhitespace(line.charAt(i - 1)))) {
                return line.substring(0, i);
            }
        }
        return line;
    }

    /** @return the directory commands run in now */
    Path dir() {
        return dir;
    }

    /** @return every command run so far with what it printed, and what the background commands printed, for failure messages */
    String transcript() {
        StringBuilder b = new StringBuilder(String.join("\n", transcript));
        for (int i = 0; i < backgroundOutput.size(); i++) {
            b.append("\n--- background ").append(backgroundNames.get(i)).append(" printed:\n").append(backgroundOutput.get(i).transcript());
        }
        return b.toString();
    }

    /**
     * Runs one command as the page has it.
     *
     * @param command a line from {@link #commands}
     * @param within  how long a foreground command may take
     * @return what it printed on standard output (empty for a background command)
     */
    String run(String command, Duration within) throws IOException, InterruptedException {
        transcript.add("$ " + command);
        if (command.startsWith("cd ")) {
            dir = dir.resolve(command.substring(3).strip()).normalize();
            assertTrue(Files.isDirectory(dir), "cd: no directory " + dir + "\n" + transcript());
            return "";
        }
        if (command.matches("kill( %\\d+)+")) {
            for (String job : command.substring(5).split(" ")) {
                stop(background.get(Integer.parseInt(job.substring(1)) - 1));
            }
            return "";
        }
        boolean inBackground = command.endsWith("&");
        String line = inBackground ? command.substring(0, command.length() - 1).strip() : command;
        String name = "doc-" + (++count);
        ProcessBuilder pb = new ProcessBuilder(argv(line)).directory(dir.toFile()).redirectError(logs.resolve(name + ".log").toFile());
        if (line.startsWith("mvn ")) {
            quickJvm(pb);
        }
        Process p = pb.start();
        StdoutLines out = new StdoutLines(p, "it-" + name);
        if (inBackground) {
            // as pasted: the next line starts at once
            background.add(p);
            backgroundNames.add("'" + line + "' (log: target/it-logs/" + name + ".log)");
            backgroundOutput.add(out);
            return "";
        }
        if (!p.waitFor(within.toMillis(), TimeUnit.MILLISECONDS)) {
            stop(p);
            fail("'" + line + "' did not finish within " + within + "; it printed:\n" + out.transcript() + "\n" + transcript());
        }
        long deadline = System.nanoTime() + Duration.ofSeconds(10).toNanos();
        String next;
        while ((next = out.next(deadline)) != null && !StdoutLines.ended(next)) {
            // drain: transcript() has it all
        }
        transcript.add(out.transcript());
        assertEquals(0, p.exitValue(), "'" + line + "' failed (log: target/it-logs/" + name + ".log): "
                + Files.readString(logs.resolve(name + ".log")) + "\n" + transcript());
        return out.transcript();
    }

    /** @return the program and arguments: ./mw is the distribution, anything else goes through bash */
    private List<String> argv(String line) {
        if (line.startsWith("./mw ") || line.equals("./mw")) {
            // As MwProcess starts the mw commands (what MW_JAVA_OPTS may give ./mw).
            List<String> argv = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString()));
            argv.addAll(MwProcess.QUICK_JVM);
            argv.addAll(List.of("-Dmw.home=" + MwProcess.CHECKOUT, "-cp", String.join(File.pathSeparator, classPath), "io.robomw.cli.Mw"));
            argv.addAll(ShellWords.split(line.substring(4).strip()));
            return argv;
        }
        if (line.startsWith("mvn ")) {
            List<String> argv = new ArrayList<>(List.of("mvn"));
            argv.addAll(mavenOptions);
            argv.addAll(ShellWords.split(line.substring(4).strip()));
            return argv;
        }
        return List.of("bash", "-c", line);
    }

    /**
     * Gives a Maven run a small collector and the quick compiler only, after any MAVEN_OPTS of the build's own: a short
     * build of a small project spends most of its time starting up and loading plugins, which C2 would compile too late
     * to repay.
     *
     * @param pb the {@code mvn} process to be
     * @return it
     */
    static ProcessBuilder quickJvm(ProcessBuilder pb) {
        pb.environment().merge("MAVEN_OPTS", String.join(" ", MwProcess.QUICK_JVM), (own, quick) -> own.isBlank() ? quick : own + " " + quick);
        return pb;
    }

    private static void stop(Process p) throws InterruptedException {
        p.destroy();
        if (!p.waitFor(15, TimeUnit.SECONDS)) {
            p.destroyForcibly();
            p.waitFor(10, TimeUnit.SECONDS);
        }
    }

    @Override
    public void close() throws InterruptedException {
        for (Process p : background) {
            stop(p);
        }
    }
}
