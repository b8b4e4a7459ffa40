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
 * A Python client script (src-it/src/test/python) run as its own process in the integration
 * tests' Python environment: {@code target/it-python}, made from {@code requirements.txt} (pinned;
 * roslibpy 2.1.0 among them) by {@code src-it/src/test/python/setup-venv}, which the build runs
 * before the integration tests and .ci/run runs too; or the Python {@code -Dit.python=PATH} names.
 * A missing environment fails the test saying how to make it: these tests are never skipped.
 */
final class PythonClient {

    static final Path SCRIPTS = MwProcess.CHECKOUT.resolve("src-it/src/test/python");

    private PythonClient() {
    }

    /** @return the Python that has roslibpy; fails, saying how to make it, if there is none */
    static Path python() throws IOException, InterruptedException {
        String given = System.getProperty("it.python");
        Path python = given != null ? Path.of(given) : MwProcess.CHECKOUT.resolve("target/it-python/bin/python");
        String make = "run src-it/src/test/python/setup-venv (python3 -m venv target/it-python and pip install -r src-it/src/test/python/requirements.txt;"
                + " .ci/run and the build do it), or name a Python that has roslibpy with -Dit.python=PATH";
        if (!Files.isExecutable(python)) {
            fail("the rosbridge tests need Python with roslibpy at " + python + ": " + make);
        }
        Process p = new ProcessBuilder(python.toString(), "-c", "import roslibpy").redirectErrorStream(true).start();
        if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
            p.destroyForcibly();
            fail(python + " lacks roslibpy (" + new String(p.getInputStream().readAllBytes()).strip() + "): " + make);
        }
        return python;
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
        List<String> command = new ArrayList<>(List.of(python().toString(), "-u", SCRIPTS.resolve(script).toString()));
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
