package io.robomw.bench;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.AgentHostBuilder;
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
    /** The system property that sets both hosts' runner spin in µs ({@code AgentHostBuilder.runnerSpin}); unset: the default. */
    static final String RUNNER_SPIN = "agent.bench.runnerSpinMicros";

    /** The system property that sets both hosts' endpoint spin in µs ({@code AgentHostBuilder.endpointSpin}); unset: the default. */
    static final String ENDPOINT_SPIN = "agent.bench.endpointSpinMicros";

    /** The system property that turns both hosts' agent wire off ({@code false}: protocol version 2, every call over RMI); unset: on. */
    static final String WIRE = "agent.bench.wire";

    /** The system property that sets both hosts' wire reply spin in µs ({@code AgentHostBuilder.wireSpin}); unset: the default. */
    static final String WIRE_SPIN = "agent.bench.wireSpinMicros";

    /** The system property that sets both hosts' wire read spin in µs ({@code AgentHostBuilder.wireReadSpin}); unset: the default. */
    static final String WIRE_READ_SPIN = "agent.bench.wireReadSpinMicros";

    /** The properties above, passed on to host B's JVM. */
    public static final java.util.List<String> PROPERTIES = java.util.List.of(RUNNER_SPIN, ENDPOINT_SPIN, WIRE, WIRE_SPIN, WIRE_READ_SPIN);

    /** @return the builder with the spins of {@value #RUNNER_SPIN}, {@value #ENDPOINT_SPIN} and {@value #WIRE_SPIN} and the wire of {@value #WIRE}, where set */
    public static AgentHostBuilder spin(AgentHostBuilder b) {
        String wire = System.getProperty(WIRE);
        if (wire != null) {
            b.wire(Boolean.parseBoolean(wire.trim()));
        }
        String wireReadSpin = System.getProperty(WIRE_READ_SPIN);
        if (wireReadSpin != null) {
            b.wireReadSpin(java.time.Duration.ofNanos(Long.parseLong(wireReadSpin.trim()) * 1000));
        }
        String wireSpin = System.getProperty(WIRE_SPIN);
        if (wireSpin != null) {
            b.wireSpin(java.time.Duration.ofNanos(Long.parseLong(wireSpin.trim()) * 1000));
        }
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
        AgentHostBuilder b = spin(AgentHost.builder("bench-b").bind("127.0.0.1").clusterKey(KEY));
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
