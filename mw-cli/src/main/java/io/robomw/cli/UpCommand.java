package io.robomw.cli;

import io.robomw.config.description.DescriptionException;
import io.robomw.config.yaml.MappingReader;
import io.robomw.config.yaml.YamlDocument;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.stream.Stream;

/**
 * {@code mw up FILE.yaml}: starts a whole setup from one file, like {@code ros2 launch} or
 * {@code docker compose up}: each entry of {@code processes:} is an {@code mw} command run in a JVM
 * of its own, in order, each started once the one before printed its ready line; their output is
 * shown with each line prefixed by the process's name. Ctrl-C (or SIGTERM) stops all of them, last
 * first; so does one of them ending by itself (then {@code mw up} exits 1 naming it).
 *
 * <pre>
 * processes:
 *   - name: nxt-brick
 *     mw: emulate nxt --world worlds/arena.yaml --robot nxt --write-robot ${run}/nxt.yaml
 *   - name: nxt-host
 *     mw: host --name nxt --port 1099 --robot ${run}/nxt.yaml --key-file cluster.key
 *     ready: ready at
 * </pre>
 *
 * Paths are relative to the file's directory, where the processes run; {@code ${run}} is a
 * directory of this run's own, removed when it ends. {@code ready} is text the process prints
 * on standard output when it is ready (default: its first line).
 */
@Command(mixinStandardHelpOptions = true, name = "up", description = {"Start a whole setup from one file (emulators, hosts, a world...): each entry of processes: is an mw command,",
        "started in order once the one before is ready; Ctrl-C stops them all. See docs/cli.md for the file."})
final class UpCommand implements java.util.concurrent.Callable<Integer> {

    @Parameters(index = "0", paramLabel = "FILE.yaml", description = "the setup")
    Path file;

    @Option(names = "--ready-timeout", defaultValue = "60s", description = "how long each process may take to print its ready line (default ${DEFAULT-VALUE})")
    Duration readyTimeout;

    @Spec
    CommandSpec spec;

    /** One process of the setup. */
    record Entry(String name, List<String> args, String ready) {
    }

    /** A started process and what it printed last. */
    private record Running(Entry entry, Process process, CompletableFuture<Void> output) {
    }

    @Override
    public Integer call() throws IOException, InterruptedException {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        List<Entry> entries;
        try {
            entries = read(file);
        } catch (DescriptionException e) {
            err.println(e.getMessage());
            err.flush();
            return Mw.USER_ERROR;
        }
        Path run = Files.createTempDirectory("mw-up-");
        Path dir = file.toAbsolutePath().getParent();
        List<Running> started = new ArrayList<>();
        CountDownLatch stop = new CountDownLatch(1);
        Thread hook = new Thread(() -> {
            stop.countDown();
            stopAll(started, out);
            deleteTree(run);
        }, "mw-up-stop");
        Runtime.getRuntime().addShutdownHook(hook);
        String ended = null;
        try {
            for (Entry e : entries) {
                List<String> command = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                        "-Dmw.home=" + System.getProperty("mw.home", "."), "-cp", DistributionClassPath.with(List.of()), Mw.class.getName()));
                e.args().forEach(a -> command.add(a.replace("${run}", run.toString())));
                Process p = new ProcessBuilder(ownSession(command)).directory(dir.toFile()).start();
                CompletableFuture<Void> ready = new CompletableFuture<>();
                CompletableFuture<Void> output = new CompletableFuture<>();
                // Standard output decides readiness; standard error (logs, errors) is shown the same way.
                Thread relay = new Thread(() -> {
                    relay(e, p.getInputStream(), ready, out);
                    output.complete(null);
                }, "mw-up-" + e.name());
                Thread relayErr = new Thread(() -> relay(e, p.getErrorStream(), null, out), "mw-up-" + e.name() + "-err");
                for (Thread t : List.of(relay, relayErr)) {
                    t.setDaemon(true);
                    t.start();
                }
                synchronized (started) {
                    started.add(new Running(e, p, output));
                }
                try {
                    ready.get(readyTimeout.toMillis(), TimeUnit.MILLISECONDS);
                } catch (java.util.concurrent.TimeoutException | java.util.concurrent.ExecutionException x) {
                    boolean gone = p.waitFor(5, TimeUnit.SECONDS);
                    ended = e.name() + (gone ? " ended with status " + p.exitValue() + " before it was ready"
                            : " printed no '" + (e.ready() == null ? "line" : e.ready()) + "' within " + Durations.format(readyTimeout));
                    break;
                }
            }
            if (ended == null) {
                synchronized (out) {
                    out.println("[mw up] " + entries.size() + " processes up; Ctrl-C stops them all");
                    out.flush();
                }
                ended = awaitFirstEnd(started, stop);
            }
        } finally {
            if (ended != null) {
                synchronized (out) {
                    out.println("[mw up] " + ended + "; stopping the others");
                    out.flush();
                }
                stopAll(started, out);
                deleteTree(run);
                try {
                    Runtime.getRuntime().removeShutdownHook(hook);
                } catch (IllegalStateException shuttingDown) {
                    // the hook stops them
                }
            }
        }
        if (ended != null) {
            err.println("mw up: " + ended);
            err.flush();
            return 1;
        }
        return 0;
    }

    /** @return which process ended by itself, or {@code null} when stopped by Ctrl-C */
    private static String awaitFirstEnd(List<Running> started, CountDownLatch stop) throws InterruptedException {
        CompletableFuture<String> first = new CompletableFuture<>();
        for (Running r : List.copyOf(started)) {
            r.process().onExit().thenAccept(p -> first.complete(stop.getCount() == 0 ? null : r.entry().name() + " ended by itself with status " + p.exitValue()));
        }
        Thread stopped = new Thread(() -> {
            try {
                stop.await();
                first.complete(null);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }, "mw-up-ctrl-c");
        stopped.setDaemon(true);
        stopped.start();
        try {
            return first.get();
        } catch (java.util.concurrent.ExecutionException e) {
            throw new IllegalStateException(e.getCause());
        }
    }

    /** Shows a process's lines prefixed with its name; completes {@code ready} (if given) at its ready line. */
    private static void relay(Entry e, java.io.InputStream stream, CompletableFuture<Void> ready, PrintWriter out) {
        try (BufferedReader r = new BufferedReader(new InputStreamReader(stream, StandardCharsets.UTF_8))) {
            for (String line; (line = r.readLine()) != null; ) {
                synchronized (out) {
                    out.println("[" + e.name() + "] " + line);
                    out.flush();
                }
                if (ready != null && (e.ready() == null || line.contains(e.ready()))) {
                    ready.complete(null);
                }
            }
        } catch (IOException x) {
            // the process is gone
        }
        if (ready != null) {
            ready.completeExceptionally(new IOException(e.name() + " ended"));
        }
    }

    /** Stops every process, the last started first: SIGTERM (their own clean stop), then SIGKILL after 15 s. */
    private static void stopAll(List<Running> started, PrintWriter out) {
        List<Running> all;
        synchronized (started) {
            all = new ArrayList<>(started);
            started.clear();
        }
        for (int i = all.size() - 1; i >= 0; i--) {
            Process p = all.get(i).process();
            String name = all.get(i).entry().name();
            if (p.isAlive()) {
                synchronized (out) {
                    out.println("[mw up] stopping " + name);
                    out.flush();
                }
            }
            p.destroy();
            try {
                if (!p.waitFor(15, TimeUnit.SECONDS)) {
                    p.destroyForcibly();
                    p.waitFor(10, TimeUnit.SECONDS);
                }
                all.get(i).output().get(5, TimeUnit.SECONDS);
                synchronized (out) {
                    out.println("[mw up] " + name + " stopped (exit status " + p.exitValue() + ")");
                    out.flush();
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                p.destroyForcibly();
            } catch (java.util.concurrent.ExecutionException | java.util.concurrent.TimeoutException e) {
                // its output is as far as it got
            }
        }
        synchronized (out) {
            if (!all.isEmpty()) {
                out.println("[mw up] stopped " + all.size() + " processes");
                out.flush();
            }
        }
    }

    /** Where setsid is, if this system has it (util-linux). */
    private static final Path SETSID = Path.of("/usr/bin/setsid");

    /**
     * Runs a process in a session (and process group) of its own, where the system can: Ctrl-C at
     * the terminal then reaches {@code mw up} alone, which stops its processes last first, as
     * {@code ros2 launch} does, instead of every process at once (a host then saw its brick's
     * emulator vanish under it). {@code setsid} runs the command in place (no fork: the process is
     * the JVM, which {@link Process#destroy()} reaches).
     */
    static List<String> ownSession(List<String> command) {
        if (!java.nio.file.Files.isExecutable(SETSID)) {
            return command;
        }
        List<String> c = new ArrayList<>(command.size() + 1);
        c.add(SETSID.toString());
        c.addAll(command);
        return c;
    }

    private static void deleteTree(Path dir) {
        try (Stream<Path> all = Files.walk(dir)) {
            for (Path p : all.sorted(Comparator.reverseOrder()).toList()) {
                Files.deleteIfExists(p);
            }
        } catch (IOException e) {
            // a temporary directory: the system removes it eventually
        }
    }

    /**
     * @param file a setup file
     * @return its processes
     * @throws DescriptionException naming the file, line and column of every problem
     */
    static List<Entry> read(Path file) {
        MappingReader root = YamlDocument.read(file);
        List<Entry> entries = new ArrayList<>();
        java.util.Set<String> names = new java.util.HashSet<>();
        List<MappingReader> processes = root.mappingList("processes");
        if (processes.isEmpty() && !root.has("processes")) {
            root.problem("processes", "a setup lists its processes: processes: [{ name: ..., mw: ... }]");
        }
        for (MappingReader p : processes) {
            String name = p.requireText("name");
            if (!names.add(name)) {
                p.problem("name", "two processes are named '" + name + "'");
            }
            String mw = p.requireText("mw");
            List<String> args;
            try {
                args = ShellWords.split(mw);
            } catch (IllegalArgumentException e) {
                p.problem("mw", e.getMessage());
                args = List.of();
            }
            if (!args.isEmpty() && (args.get(0).equals("up") || args.get(0).equals("mw"))) {
                p.problem("mw", args.get(0).equals("mw") ? "give the command without 'mw': emulate ..., host ..." : "mw up cannot start mw up");
            }
            entries.add(new Entry(name, args, p.text("ready").orElse(null)));
            p.finish();
        }
        root.finish();
        root.problems().throwIfAny();
        return entries;
    }
}
