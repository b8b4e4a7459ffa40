package io.robomw.bench;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;

import java.io.BufferedReader;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;

/**
 * Host B of {@link AgentBenchmark}, in its own JVM: an agent host on 127.0.0.1 with the
 * benchmark's cluster key, in memory mode ({@code memory}) or durable mode ({@code durable DIR}).
 * This JVM's class path does not hold the benchmark agent's class: its code arrives as an archive.
 *
 * <p>Stdout carries only the protocol: {@code ADDRESS rmi://...} once the host listens; the
 * command {@code WIRE} answers {@code WIRE bytesIn bytesOut} (the host's RMI server sockets);
 * {@code exit} or the end of stdin closes the host and ends the JVM.
 */
public final class AgentBenchPeer {

    static final ClusterKey KEY = ClusterKey.fromPassphrase("robomw agent benchmark");
    /** The system property that sets both hosts' runner spin in µs ({@code AgentHost.Builder.runnerSpin}); unset: the default. */
    static final String RUNNER_SPIN = "agent.bench.runnerSpinMicros";

    /** The system property that sets both hosts' endpoint spin in µs ({@code AgentHost.Builder.endpointSpin}); unset: the default. */
    static final String ENDPOINT_SPIN = "agent.bench.endpointSpinMicros";

    /** @return the builder with the spins of {@value #RUNNER_SPIN} and {@value #ENDPOINT_SPIN}, where set */
    static AgentHost.Builder spin(AgentHost.Builder b) {
        String micros = System.getProperty(RUNNER_SPIN);
        if (micros != null) {
            b.runnerSpin(java.time.Duration.ofNanos(Long.parseLong(micros.trim()) * 1000));
        }
        String endpoint = System.getProperty(ENDPOINT_SPIN);
        if (endpoint != null) {
            b.endpointSpin(java.time.Duration.ofNanos(Long.parseLong(endpoint.trim()) * 1000));
        }
        return b;
    }

    private AgentBenchPeer() {
    }

    /**
     * @param args {@code memory} or {@code durable DIR}
     * @throws Exception if the host cannot start
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(System.out, true, StandardCharsets.UTF_8);
        AgentHost.Builder b = spin(AgentHost.builder("bench-b").bind("127.0.0.1").clusterKey(KEY));
        if (args.length > 1 && args[0].equals("durable")) {
            b.store(Path.of(args[1]));
        }
        try (AgentHost host = b.start()) {
            out.println("ADDRESS " + host.address());
            BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            String line;
            while ((line = in.readLine()) != null && !line.equals("exit")) {
                if (line.equals("WIRE")) {
                    out.println("WIRE " + host.wireBytesIn() + " " + host.wireBytesOut());
                } else {
                    out.println("ERR unknown command " + line);
                }
            }
        }
        System.exit(0);
    }
}
