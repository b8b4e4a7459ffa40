package io.robomw.it.net;

import io.robomw.it.demo.MwProcess;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

/**
 * One host of a {@link NetLab}: a network namespace with the address {@link #ip()} on the lab's
 * bridge. Processes started here ({@code ip netns exec NS java ...}) see only this host's network.
 *
 * @param lab       the lab
 * @param name      its short name
 * @param namespace its namespace
 * @param ip        its address on the bridge
 */
public record LabHost(NetLab lab, String name, String namespace, String ip) {

    /** Options every JVM of a lab runs with: small heaps, the serial collector, C1 only (two cores are shared by up to four JVMs). */
    static final List<String> SMALL_JVM = List.of("-Xmx160m", "-Xss512k", "-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1", "-XX:CICompilerCount=1",
            "--enable-native-access=ALL-UNNAMED");
    /** How long a JVM may take to start here, on a loaded machine. */
    static final Duration START = Duration.ofSeconds(90);

    /**
     * Starts a main class of this JVM's class path here (the test's own programs: they have the
     * example agents and the test classes).
     *
     * @param logName   the log's name ({@code target/it-logs/NAME.log})
     * @param mainClass the class
     * @param args      its arguments
     * @return the process
     * @throws IOException if it cannot start
     */
    public LabProcess java(String logName, String mainClass, String... args) throws IOException {
        return java(logName, List.of(), mainClass, args);
    }

    /**
     * {@link #java(String, String, String...)} with JVM options.
     *
     * @param logName   the log's name
     * @param jvm       JVM options (system properties)
     * @param mainClass the class
     * @param args      its arguments
     * @return the process
     * @throws IOException if it cannot start
     */
    public LabProcess java(String logName, List<String> jvm, String mainClass, String... args) throws IOException {
        return launch(logName, System.getProperty("java.class.path"), jvm, mainClass, List.of(args));
    }

    /**
     * Starts an {@code mw} command here, on the middleware's class path only (no example agents, no
     * test classes: agents' code has to travel), as {@code ./mw} runs it.
     *
     * @param logName the log's name
     * @param jvm     extra JVM options
     * @param args    the command and its options
     * @return the process
     * @throws IOException if it cannot start
     */
    public LabProcess mw(String logName, List<String> jvm, String... args) throws IOException {
        List<String> options = new ArrayList<>(jvm);
        options.add("-Dmw.home=" + MwProcess.CHECKOUT);
        return launch(logName, MwProcess.middlewareOnlyClassPath(), options, "io.robomw.cli.Mw", List.of(args));
    }

    /**
     * Starts {@code mw host NAME} here, bound to this host's address on port 1099, and waits for
     * its ready line and its messaging line.
     *
     * @param hostName the agent host's name
     * @param keyFile  the cluster key file
     * @param extra    more {@code mw host} options
     * @return the running host
     * @throws IOException if it cannot start
     */
    public LabProcess agentHost(String hostName, Path keyFile, String... extra) throws IOException {
        List<String> args = new ArrayList<>(List.of("host", "--name", hostName, "--bind", ip, "--port", "1099", "--key-file", keyFile.toString(),
                "--beacon", "off"));
        args.addAll(List.of(extra));
        LabProcess p = mw(lab.tag() + "-" + hostName, List.of(), args.toArray(String[]::new));
        p.expect("agent host " + hostName + " ready at", START);
        p.expect("messaging at", START);
        return p;
    }

    /** @return the address {@code mw host NAME} started by {@link #agentHost} has */
    public String rmi(String hostName) {
        return "rmi://" + ip + ":1099/" + hostName;
    }

    private LabProcess launch(String logName, String classPath, List<String> jvm, String mainClass, List<String> args) throws IOException {
        List<String> command = new ArrayList<>(List.of("ip", "netns", "exec", namespace, Path.of(System.getProperty("java.home"), "bin", "java").toString()));
        command.addAll(SMALL_JVM);
        command.addAll(jvm);
        command.addAll(List.of("-cp", classPath, mainClass));
        command.addAll(args);
        LabProcess p = LabProcess.start(logName, command, MwProcess.CHECKOUT);
        lab.started(p);
        return p;
    }
}
