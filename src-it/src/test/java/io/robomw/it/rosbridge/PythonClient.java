package io.robomw.it.rosbridge;

import io.robomw.it.StdoutLines;
import io.robomw.it.demo.MwProcess;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.fail;

/**
 * A Python client script (src-it/src/test/python) run in the tests' venv, as its own process:
 * {@code src-it/target/python-venv}, made by {@code src-it/src/test/python/setup-venv.sh} (which
 * .ci/run calls) with the pinned requirements. A missing venv fails the test saying how to make
 * it: these tests are never skipped.
 */
final class PythonClient {

    static final Path SCRIPTS = MwProcess.CHECKOUT.resolve("src-it/src/test/python");
    static final Path PYTHON = MwProcess.CHECKOUT.resolve("src-it/target/python-venv/bin/python");

    private PythonClient() {
    }

    /** Fails, saying how to make it, if the venv with roslibpy is not there. */
    static void requireVenv() {
        if (!Files.isExecutable(PYTHON)) {
            fail("no Python venv with roslibpy at " + PYTHON + ": run " + SCRIPTS.resolve("setup-venv.sh")
                    + " (needs python3 and its venv module; .ci/run does this before mvn verify)");
        }
    }

    /** The outcome of a script: its exit status and everything it printed. */
    record Run(int exit, String output) {
    }

    /**
     * Runs a script to its end.
     *
     * @param script its file name in src-it/src/test/python
     * @param env    variables to set (ROSLIBPY_TRANSPORT)
     * @param within the longest it may take; then it is killed and the test fails
     * @param args   its arguments
     * @return how it ended
     */
    static Run run(String script, Map<String, String> env, Duration within, String... args) throws IOException, InterruptedException {
        requireVenv();
        List<String> command = new ArrayList<>(List.of(PYTHON.toString(), "-u", SCRIPTS.resolve(script).toString()));
        command.addAll(List.of(args));
        ProcessBuilder pb = new ProcessBuilder(command).redirectErrorStream(true);
        pb.environment().putAll(env);
        Process p = pb.start();
        StdoutLines lines = new StdoutLines(p, "it-python-" + script);
        try {
            if (!p.waitFor(within.toMillis(), TimeUnit.MILLISECONDS)) {
                fail(script + " " + String.join(" ", args) + " did not finish within " + within + "; it printed:\n" + drain(lines));
            }
            return new Run(p.exitValue(), drain(lines));
        } finally {
            p.destroyForcibly();
            p.waitFor(10, TimeUnit.SECONDS);
        }
    }

    /** Everything the process printed, once its output has ended. */
    private static String drain(StdoutLines lines) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
        while (true) {
            String line = lines.next(deadline);
            if (line == null || StdoutLines.ended(line)) {
                return lines.transcript();
            }
        }
    }
}
