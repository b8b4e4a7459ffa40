package io.robomw.it.net;

import org.junit.jupiter.api.Assumptions;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Hosts on a real network, on one machine: each a Linux network namespace with one veth whose
 * other end is on a bridge in a namespace of its own (nothing touches the machine's own
 * namespace), addresses {@code 10.77.0.1} upwards on {@code 10.77.0.0/24}. Faults are nftables
 * rules in the bridge's namespace, in the {@code bridge} family's forward hook, so they act
 * between hosts and never on a host's own sockets (dropping in a sender's output hook makes
 * {@code sendto} fail with EPERM instead of losing the packet):
 * <ul>
 *   <li>{@link #isolate(LabHost)}: the host can reach nobody and nobody it (packets dropped
 *       silently, as a pulled cable or a dead switch port: connects time out);</li>
 *   <li>{@link #partition(LabHost, LabHost)}: two hosts cannot reach each other, both reach the rest;</li>
 *   <li>{@link #loss(int)}: every packet between hosts is dropped with that probability
 *       ({@code numgen random mod 100 < P});</li>
 *   <li>{@link #heal()}: every rule removed.</li>
 * </ul>
 * The kernel has no {@code netem}, so there is no in-kernel delay; {@link DelayRelay} is the
 * user-space relay that adds one to the connections made through it.
 *
 * <p><b>Cleanup.</b> Namespaces are named {@code rmwit-PID-...} after this JVM's process id.
 * {@link #close()} kills every process left in them and deletes them (deleting a namespace deletes
 * its veths and the bridge); a shutdown hook does the same if the JVM is stopped first; and every
 * new lab first deletes the {@code rmwit-} namespaces of JVMs no longer running, so a run killed
 * with SIGKILL leaves nothing behind the next run.
 *
 * <p><b>A machine where namespaces cannot be made</b> (not root, no iproute2 or nftables): opening a
 * lab fails with a message that says what is missing and that {@code .ci/run} installs it. The tests
 * are not skipped silently: a developer without root skips them explicitly with
 * {@code -Dnetlab=off}, and the test report then lists them as skipped with that reason.
 */
public final class NetLab implements AutoCloseable {

    /** Prefix of every namespace a lab makes. */
    static final String PREFIX = "rmwit-";
    private static final Pattern OURS = Pattern.compile("^" + PREFIX + "(\\d+)-\\S+");
    private static final Duration COMMAND = Duration.ofSeconds(30);
    /** The nftables table (family bridge) in the switch namespace that holds the faults. */
    private static final String TABLE = "faults";

    private final String tag;
    private final String sw;
    private final List<LabHost> hosts = new ArrayList<>();
    private final List<LabProcess> processes = new ArrayList<>();
    private final Thread hook;
    private boolean closed;

    private NetLab(String tag) {
        this.tag = tag;
        this.sw = PREFIX + ProcessHandle.current().pid() + "-" + tag + "-sw";
        this.hook = new Thread(this::close, "netlab-cleanup-" + tag);
    }

    /**
     * Makes the switch: a namespace with a bridge, and the fault table.
     *
     * @param tag a short name for this lab (letters and digits), in its namespaces' names
     * @return the lab
     * @throws IOException if the machine cannot make namespaces (the message says why)
     */
    public static NetLab open(String tag) throws IOException {
        Assumptions.assumeFalse("off".equals(System.getProperty("netlab")),
                "-Dnetlab=off: the tests with hosts in network namespaces are skipped on request");
        if (!tag.matches("[a-z0-9]{1,8}")) {
            throw new IllegalArgumentException("lab tag '" + tag + "': 1 to 8 lower-case letters and digits");
        }
        requireTools();
        removeLeftovers();
        NetLab lab = new NetLab(tag);
        Runtime.getRuntime().addShutdownHook(lab.hook);
        try {
            lab.run("ip", "netns", "add", lab.sw);
            lab.run("ip", "-n", lab.sw, "link", "add", "br0", "type", "bridge");
            lab.run("ip", "-n", lab.sw, "link", "set", "br0", "up");
            lab.nft("add table bridge " + TABLE + "; add chain bridge " + TABLE + " between { type filter hook forward priority 0; }");
        } catch (IOException | RuntimeException e) {
            lab.close();
            throw e;
        }
        return lab;
    }

    private static void requireTools() throws IOException {
        String why = null;
        if (!new java.io.File("/usr/sbin/ip").canExecute() && !new java.io.File("/sbin/ip").canExecute() && !onPath("ip")) {
            why = "iproute2's ip is not installed (apt-get install iproute2)";
        } else if (!new java.io.File("/usr/sbin/nft").canExecute() && !onPath("nft")) {
            why = "nftables' nft is not installed (apt-get install nftables)";
        } else {
            String user = System.getProperty("user.name");
            Result r = exec(List.of("ip", "netns", "list"));
            if (r.status != 0) {
                why = "'ip netns list' failed as user " + user + ": " + r.output.strip();
            }
        }
        if (why != null) {
            throw new IOException("this machine cannot make the network namespaces these tests need: " + why
                    + ". They need root (CI runs as root) and iproute2 and nftables, which .ci/run installs;"
                    + " without them run the build with -Dnetlab=off to skip these tests explicitly (they are then reported as skipped).");
        }
    }

    private static boolean onPath(String tool) {
        for (String dir : System.getenv().getOrDefault("PATH", "").split(java.io.File.pathSeparator)) {
            if (new java.io.File(dir, tool).canExecute()) {
                return true;
            }
        }
        return false;
    }

    /** Deletes the namespaces of labs whose JVM is gone (a run killed before it could clean up). */
    static void removeLeftovers() throws IOException {
        for (String ns : namespaces()) {
            Matcher m = OURS.matcher(ns);
            if (m.matches() && !ProcessHandle.of(Long.parseLong(m.group(1))).map(ProcessHandle::isAlive).orElse(false)) {
                deleteNamespace(ns);
            }
        }
    }

    /** @return the names of the namespaces on this machine now */
    static List<String> namespaces() throws IOException {
        Result r = exec(List.of("ip", "netns", "list"));
        List<String> names = new ArrayList<>();
        for (String line : r.output.split("\n")) {
            if (!line.isBlank()) {
                names.add(line.strip().split("\\s+")[0]);
            }
        }
        return names;
    }

    /** Kills what runs in a namespace and deletes it. */
    private static void deleteNamespace(String ns) throws IOException {
        Result pids = exec(List.of("ip", "netns", "pids", ns));
        for (String p : pids.output.split("\\s+")) {
            if (p.matches("\\d+")) {
                ProcessHandle.of(Long.parseLong(p)).ifPresent(ProcessHandle::destroyForcibly);
            }
        }
        exec(List.of("ip", "netns", "del", ns));
    }

    /**
     * Adds a host: a namespace with loopback up and one veth on the bridge.
     *
     * @param name a short name (letters and digits), in its namespace's name
     * @return the host
     * @throws IOException if it cannot be made
     */
    public LabHost host(String name) throws IOException {
        int index = hosts.size() + 1;
        String ns = PREFIX + ProcessHandle.current().pid() + "-" + tag + "-" + name;
        String ip = "10.77.0." + index;
        String port = "p" + index;
        run("ip", "netns", "add", ns);
        LabHost h = new LabHost(this, name, ns, ip);
        hosts.add(h);
        run("ip", "link", "add", "eth0", "netns", ns, "type", "veth", "peer", "name", port, "netns", sw);
        run("ip", "-n", sw, "link", "set", port, "master", "br0");
        run("ip", "-n", sw, "link", "set", port, "up");
        run("ip", "-n", ns, "link", "set", "lo", "up");
        run("ip", "-n", ns, "addr", "add", ip + "/24", "dev", "eth0");
        run("ip", "-n", ns, "link", "set", "eth0", "up");
        return h;
    }

    /** @return the lab's tag, which the logs of its processes start with */
    public String tag() {
        return tag;
    }

    /** Remembers a process to kill at {@link #close()} if it still runs. */
    void started(LabProcess p) {
        synchronized (processes) {
            processes.add(p);
        }
    }

    /**
     * Cuts a host off from every other: nothing it sends crosses the bridge, nothing reaches it.
     *
     * @param h the host
     * @throws IOException if the rules cannot be added
     */
    public void isolate(LabHost h) throws IOException {
        nft("add rule bridge " + TABLE + " between ip saddr " + h.ip() + " drop; add rule bridge " + TABLE + " between ip daddr " + h.ip() + " drop");
    }

    /**
     * Cuts two hosts off from each other; each still reaches the others.
     *
     * @param a one
     * @param b the other
     * @throws IOException if the rules cannot be added
     */
    public void partition(LabHost a, LabHost b) throws IOException {
        nft("add rule bridge " + TABLE + " between ip saddr " + a.ip() + " ip daddr " + b.ip() + " drop; add rule bridge " + TABLE
                + " between ip saddr " + b.ip() + " ip daddr " + a.ip() + " drop");
    }

    /**
     * Drops every IP packet between any two hosts with a probability.
     *
     * @param percent the share of packets dropped, 1 to 99
     * @throws IOException if the rule cannot be added
     */
    public void loss(int percent) throws IOException {
        if (percent < 1 || percent > 99) {
            throw new IllegalArgumentException("loss " + percent + "%: between 1 and 99");
        }
        nft("add rule bridge " + TABLE + " between meta protocol ip numgen random mod 100 < " + percent + " drop");
    }

    /** Removes every fault: all hosts reach each other again. @throws IOException if the rules cannot be removed */
    public void heal() throws IOException {
        nft("flush chain bridge " + TABLE + " between");
    }

    /** @return the packets the fault rules dropped so far (their counters), for the figures */
    public long dropped() throws IOException {
        Result r = exec(List.of("ip", "netns", "exec", sw, "nft", "list", "chain", "bridge", TABLE, "between"));
        long n = 0;
        Matcher m = Pattern.compile("packets (\\d+)").matcher(r.output);
        while (m.find()) {
            n += Long.parseLong(m.group(1));
        }
        return n;
    }

    private void nft(String script) throws IOException {
        // counters on every rule, so that dropped() can tell how much a fault took
        run("ip", "netns", "exec", sw, "nft", script.replace(" drop", " counter drop"));
    }

    private void run(String... command) throws IOException {
        Result r = exec(List.of(command));
        if (r.status != 0) {
            throw new IOException("'" + String.join(" ", command) + "' failed (exit " + r.status + "): " + r.output.strip());
        }
    }

    private record Result(int status, String output) {
    }

    private static Result exec(List<String> command) throws IOException {
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        try {
            if (!p.waitFor(COMMAND.toSeconds(), TimeUnit.SECONDS)) {
                p.destroyForcibly();
                throw new IOException("'" + String.join(" ", command) + "' did not finish within " + COMMAND);
            }
        } catch (InterruptedException e) {
            p.destroyForcibly();
            Thread.currentThread().interrupt();
            throw new IOException("interrupted running '" + String.join(" ", command) + "'", e);
        }
        return new Result(p.exitValue(), new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8));
    }

    /** Stops every process started in the lab (SIGTERM, then SIGKILL), then deletes every namespace it made. */
    @Override
    public synchronized void close() {
        if (closed) {
            return;
        }
        closed = true;
        List<LabProcess> started;
        synchronized (processes) {
            started = new ArrayList<>(processes);
        }
        for (int i = started.size() - 1; i >= 0; i--) {
            started.get(i).close();
        }
        List<String> all = new ArrayList<>();
        hosts.forEach(h -> all.add(h.namespace()));
        all.add(sw);
        for (String ns : all) {
            try {
                deleteNamespace(ns);
            } catch (IOException e) {
                System.err.println("netlab: cannot delete namespace " + ns + ": " + e.getMessage());
            }
        }
        if (Thread.currentThread() != hook) {
            try {
                Runtime.getRuntime().removeShutdownHook(hook);
            } catch (IllegalStateException e) {
                // the JVM is shutting down: the hook runs (this close) anyway
            }
        }
    }
}
