package io.robomw.cli;

import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

import java.io.IOException;
import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;

/**
 * {@code mw run Program.java [args]}: runs a program on the distribution's class path, in a JVM
 * of its own (the Java launcher's single-file source mode for a {@code .java} file, or a main
 * class from {@code --cp}). Its input and output are the terminal's; {@code mw run} exits with
 * its status. Everything after the program is the program's (options too).
 */
@Command(mixinStandardHelpOptions = true, name = "run", description = {"Run a Java program on RoboMW's class path: a single .java file (no build), or a main class of --cp.",
        "Example: mw run examples/FirstProgram.java nxt.yaml"})
final class RunCommand implements Callable<Integer> {

    @Option(names = "--cp", paramLabel = "PATH", split = ":|;", description = "more class path entries after RoboMW's (your jars or classes)")
    List<String> extra = new ArrayList<>();

    @Option(names = {"-J", "--java-option"}, paramLabel = "OPTION", description = "an option for the program's JVM, e.g. -J-Xmx256m")
    List<String> javaOptions = new ArrayList<>();

    @Parameters(index = "0", paramLabel = "PROGRAM", description = "Program.java, or the main class of a --cp entry")
    String program;

    @Parameters(index = "1..*", paramLabel = "ARG", description = "the program's arguments")
    List<String> args = new ArrayList<>();

    @Spec
    CommandSpec spec;

    @Override
    public Integer call() throws IOException, InterruptedException {
        PrintWriter err = spec.commandLine().getErr();
        boolean source = program.endsWith(".java");
        if (source && !Files.isRegularFile(Path.of(program))) {
            err.println("mw run: no such file: " + program);
            err.flush();
            return Mw.USER_ERROR;
        }
        if (!source && !program.matches("[\\p{L}_$][\\p{L}\\p{N}_$]*(\\.[\\p{L}_$][\\p{L}\\p{N}_$]*)*")) {
            err.println("mw run: '" + program + "' is neither a .java file nor a class name (give Program.java, or --cp JAR and the main class)");
            err.flush();
            return Mw.USER_ERROR;
        }
        for (String a : args) {
            // a robot or world file named as an argument may still be being written by a command started just before
            if ((a.endsWith(".yaml") || a.endsWith(".yml")) && !a.contains("://")) {
                AwaitedFile.await(Path.of(a), spec, "mw run");
            }
        }
        List<String> command = new ArrayList<>();
        command.add(Path.of(System.getProperty("java.home"), "bin", "java").toString());
        command.addAll(javaOptions);
        command.add("-cp");
        command.add(DistributionClassPath.with(extra));
        command.add(program);
        command.addAll(args);
        Process p = new ProcessBuilder(command).inheritIO().start();
        Thread stop = new Thread(() -> {
            p.destroy();
            try {
                p.waitFor();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }, "mw-run-stop");
        Runtime.getRuntime().addShutdownHook(stop);
        try {
            return p.waitFor();
        } finally {
            try {
                Runtime.getRuntime().removeShutdownHook(stop);
            } catch (IllegalStateException e) {
                // shutting down already: the hook stops the program
            }
        }
    }
}
