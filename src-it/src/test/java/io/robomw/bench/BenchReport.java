package io.robomw.bench;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;

/**
 * The table of {@code bench/all}: reads every sample the benchmarks printed (one {@code BENCH}
 * line per figure per fresh JVM, collected as {@code sample-number TAB line}) and writes, per
 * case, the number of runs, the median, min and max, the ratio of the medians to the case's
 * baseline in the same run with the spread of the per-round ratios ({@link #roundRatios}), the ceiling that bounds it (measured in the same run by
 * {@link Ceilings} or the harness), and the target, under the machine's description.
 *
 * <p>Usage: {@code BenchReport SAMPLES MACHINE OUT.md}. The catalogue below names every known
 * case; a case it does not know is listed with its id.
 */
public final class BenchReport {

    /** @return the line a harness prints for one figure of one run */
    static String line(String id, double value, String unit) {
        return String.format(Locale.ROOT, "BENCH %s %.6g %s", id, value, unit);
    }

    /**
     * A known case.
     *
     * @param id       its id in the BENCH lines
     * @param label    what it is
     * @param higher   whether higher is better
     * @param baseline the id of its baseline in the same run, or null
     * @param ceiling  ids of the ceilings that bound it (shown next to it), may be empty
     * @param target   the target the issue sets, or ""
     */
    record Case(String id, String label, boolean higher, String baseline, List<String> ceiling, String target) {
    }

    private static final List<Case> CATALOGUE = List.of(
            // ceilings
            new Case("ceiling.tcp-pingpong-64B", "loopback TCP ping-pong, 64 B, plain sockets, two threads (p50)", false, null, List.of(), ""),
            new Case("ceiling.tcp-bulk", "loopback TCP bulk, one direction, 64 KiB writes", true, null, List.of(), ""),
            new Case("ceiling.copy-1MiB", "copy 1 MiB into an existing array", true, null, List.of(), ""),
            new Case("ceiling.copy-fresh-1MiB", "copy 1 MiB into a fresh array (Arrays.copyOf)", true, null, List.of(), ""),
            new Case("ceiling.hmac-sha256-1MiB", "HMAC-SHA256 over 1 MiB (JDK)", true, null, List.of(), ""),
            new Case("ceiling.gmac-aes256-1MiB", "AES-256-GCM as a MAC (GMAC) over 1 MiB (JDK)", true, null, List.of(), ""),
            new Case("ceiling.gcm-tag-aes256-1MiB", "AES-256-GCM tag over 1 MiB, the JDK's provider (16 KiB chunks)", true, null, List.of(), ""),
            new Case("ceiling.gcm-tag-accp-1MiB", "AES-256-GCM tag over 1 MiB, ACCP, as agent hosts tag frames where it loads (64 KiB chunks)", true, null, List.of(), ""),
            new Case("ceiling.aes256-gcm-encrypt-1MiB", "AES-256-GCM encryption of 1 MiB (JDK)", true, null, List.of(), ""),
            new Case("ceiling.hmac-sha256-600B", "HMAC-SHA256 of a 600-byte call", false, null, List.of(), ""),
            new Case("ceiling.gmac-aes256-600B", "GMAC of a 600-byte call (init + tag)", false, null, List.of(), ""),
            new Case("ceiling.gcm-tag-aes256-600B", "AES-256-GCM tag of a 600-byte call, the JDK's provider", false, null, List.of(), ""),
            new Case("ceiling.gcm-tag-accp-600B", "AES-256-GCM tag of a 600-byte call, ACCP, as agent hosts make it where it loads", false, null, List.of(), ""),
            new Case("ceiling.fdatasync-512B", "fdatasync after a 512-byte overwrite (p50)", false, null, List.of(), ""),
            // simulation
            new Case("sim.n1000.grid50", "swarm N = 1000, grid sensing, physics 50 Hz, 8 IR at 10 Hz", true, "sim.n1000.naive50",
                    List.of("sim.n1000.physics"), "≥ 30×"),
            new Case("sim.n1000.naive50", "swarm N = 1000, naive dyn4j ray casts (baseline)", true, null, List.of(), ""),
            new Case("sim.n1000.physics", "N = 1000, dyn4j step alone (ceiling of the world's physics)", true, null, List.of(), ""),
            new Case("sim.n1000.step-per-robot", "N = 1000, dyn4j step cost per robot", false, null, List.of(), ""),
            new Case("sim.n1000.heap-per-robot", "N = 1000, live heap per robot after a full GC", false, null, List.of(), ""),
            new Case("sim.n1000.heap-per-robot-full", "N = 1000, dyn4j, live heap per robot after the run, trajectories full", false, null,
                    List.of(), ""),
            new Case("sim.n1000.swarm50", "swarm N = 1000, grid sensing, **swarm physics engine**, physics 50 Hz, 8 IR at 10 Hz", true,
                    "sim.n1000.naive50", List.of("sim.n1000.swarm-physics"), "≥ 30×"),
            new Case("sim.n1000.swarm-physics", "N = 1000, swarm engine's step alone", true, null, List.of(), ""),
            new Case("sim.n1000.swarm-step-per-robot", "N = 1000, swarm engine's step cost per robot", false, null, List.of(), ""),
            new Case("sim.n1000.swarm-heap-per-robot", "N = 1000, swarm engine, live heap per robot after a full GC", false, null, List.of(), ""),
            new Case("sim.n1000.swarm-heap-per-robot-full", "N = 1000, swarm engine, live heap per robot after the run, trajectories full", false,
                    null, List.of(), ""),
            new Case("sim.n10000.grid50", "swarm N = 10,000, grid sensing, physics 50 Hz, 8 IR at 10 Hz", true, "sim.n10000.naive50",
                    List.of("sim.n10000.physics"), "≥ 2.5×"),
            new Case("sim.n10000.naive50", "swarm N = 10,000, naive dyn4j ray casts (baseline)", true, null, List.of(), ""),
            new Case("sim.n10000.physics", "N = 10,000, dyn4j step alone", true, null, List.of(), ""),
            new Case("sim.n10000.step-per-robot", "N = 10,000, dyn4j step cost per robot", false, null, List.of(), ""),
            new Case("sim.n10000.heap-per-robot", "N = 10,000, live heap per robot after a full GC", false, null, List.of(), ""),
            new Case("sim.n10000.heap-per-robot-full", "N = 10,000, dyn4j, live heap per robot after the run, trajectories full", false, null,
                    List.of(), ""),
            new Case("sim.n10000.swarm50", "swarm N = 10,000, grid sensing, **swarm physics engine**, physics 50 Hz, 8 IR at 10 Hz", true,
                    "sim.n10000.naive50", List.of("sim.n10000.swarm-physics"), "≥ 8× (issue 36)"),
            new Case("sim.n10000.swarm-physics", "N = 10,000, swarm engine's step alone", true, null, List.of(), ""),
            new Case("sim.n10000.swarm-step-per-robot", "N = 10,000, swarm engine's step cost per robot", false, null, List.of(), ""),
            new Case("sim.n10000.swarm-heap-per-robot", "N = 10,000, swarm engine, live heap per robot after a full GC", false, null,
                    List.of(), ""),
            new Case("sim.n10000.swarm-heap-per-robot-full", "N = 10,000, swarm engine, live heap per robot after the run, trajectories full",
                    false, null, List.of(), ""),
            new Case("sim.n100000.swarm50", "swarm N = 100,000, grid sensing, swarm physics engine, physics 50 Hz, 8 IR at 10 Hz (no naive "
                    + "baseline at this size: see docs/benchmarks.md)", true, null, List.of("sim.n100000.swarm-physics"), "≥ 0.5× (issue 36)"),
            new Case("sim.n100000.swarm-physics", "N = 100,000, swarm engine's step alone", true, null, List.of(), ""),
            new Case("sim.n100000.swarm-step-per-robot", "N = 100,000, swarm engine's step cost per robot", false, null, List.of(), ""),
            new Case("sim.n100000.swarm-heap-per-robot", "N = 100,000, swarm engine, live heap per robot at load", false, null, List.of(), ""),
            new Case("sim.n100000.swarm-heap-per-robot-full", "N = 100,000, swarm engine, live heap per robot after the run, trajectories full",
                    false, null, List.of(), "≤ 6 KiB (issue 36)"),
            // messaging
            new Case("msg.rr-raw", "request/reply 64 B, raw java.net.Socket ping-pong between JVMs (baseline), p50", false, null,
                    List.of("ceiling.tcp-pingpong-64B"), ""),
            new Case("msg.rr-zmq", "request/reply 64 B, JeroMQ REQ/REP, p50", false, "msg.rr-raw", List.of(), ""),
            new Case("msg.rr-tcp", "request/reply 64 B, RoboMW tcp (reply spin 50 µs), p50", false, "msg.rr-raw", List.of("ceiling.tcp-pingpong-64B"), ""),
            new Case("msg.rr-tcp-nospin", "request/reply 64 B, RoboMW tcp, no spin, p50", false, "msg.rr-raw", List.of("ceiling.tcp-pingpong-64B"),
                    "≤ 1.1× the raw socket (ratio ≥ 0.91)"),
            new Case("msg.rr-rmi", "request/reply 64 B, RoboMW rmi, p50", false, "msg.rr-raw", List.of(), ""),
            new Case("msg.rr-udp", "request/reply 64 B, RoboMW udp, p50", false, "msg.rr-raw", List.of(), ""),
            new Case("msg.rr-multicast", "request/reply 64 B, RoboMW multicast, p50", false, "msg.rr-raw", List.of(), ""),
            new Case("msg.ps-zmq", "publish/subscribe 64 B, JeroMQ PUB/SUB (baseline)", true, null, List.of("ceiling.tcp-bulk"), ""),
            new Case("msg.ps-tcp", "publish/subscribe 64 B, RoboMW tcp", true, "msg.ps-zmq", List.of("ceiling.tcp-bulk"), "≥ 1.5× JeroMQ"),
            new Case("msg.ps-rmi", "publish/subscribe 64 B, RoboMW rmi", true, "msg.ps-zmq", List.of(), ""),
            new Case("msg.ps-udp", "publish/subscribe 64 B, RoboMW udp", true, "msg.ps-zmq", List.of(), ""),
            new Case("msg.ps-multicast", "publish/subscribe 64 B, RoboMW multicast", true, "msg.ps-zmq", List.of(), ""),
            // agents
            new Case("agents.memory.0B", "agent warm A→B→A, 0 B payload, memory mode, p50", false, "agents.jade.0B",
                    List.of("ceiling.tcp-pingpong-64B", "ceiling.gcm-tag-accp-600B"), "≥ 10× JADE"),
            new Case("agents.memory.10KB", "agent warm A→B→A, 10 KB, memory mode, p50", false, "agents.jade.10KB", List.of(), "≥ 10× JADE"),
            new Case("agents.memory.1MB", "agent warm A→B→A, 1 MB, memory mode, p50", false, "agents.jade.1MB",
                    List.of("ceiling.tcp-bulk", "ceiling.copy-fresh-1MiB", "ceiling.gcm-tag-accp-1MiB"), "≥ 2× JADE"),
            new Case("agents.durable.0B", "agent warm A→B→A, 0 B, durable mode, p50", false, "agents.jade.0B", List.of("ceiling.fdatasync-512B"),
                    "≤ 500 µs"),
            new Case("agents.durable.10KB", "agent warm A→B→A, 10 KB, durable mode, p50", false, "agents.jade.10KB", List.of(), ""),
            new Case("agents.durable.1MB", "agent warm A→B→A, 1 MB, durable mode, p50", false, "agents.jade.1MB", List.of(), ""),
            new Case("agents.memory.0B.cpu", "processor time of both hosts' JVMs per warm round trip, 0 B, memory mode", false, null, List.of(), ""),
            new Case("agents.memory.10KB.cpu", "processor time per round trip, 10 KB, memory mode", false, null, List.of(), ""),
            new Case("agents.memory.1MB.cpu", "processor time per round trip, 1 MB, memory mode", false, null, List.of(), ""),
            new Case("agents.durable.0B.cpu", "processor time per round trip, 0 B, durable mode", false, null, List.of(), ""),
            new Case("agents.durable.10KB.cpu", "processor time per round trip, 10 KB, durable mode", false, null, List.of(), ""),
            new Case("agents.durable.1MB.cpu", "processor time per round trip, 1 MB, durable mode", false, null, List.of(), ""),
            new Case("agents.jade.0B", "JADE 4.3 doMove A→B→A, 0 B (baseline), p50", false, null, List.of(), ""),
            new Case("agents.jade.10KB", "JADE doMove A→B→A, 10 KB (baseline), p50", false, null, List.of(), ""),
            new Case("agents.jade.1MB", "JADE doMove A→B→A, 1 MB (baseline), p50", false, null, List.of(), ""),
            // many agents at once (issue 36): ManyAgentsBenchmark
            new Case("many.robomw.hops-per-s", "1,000 agents hopping among 4 host JVMs, RoboMW: hops per second", true, "many.jade.hops-per-s",
                    List.of(), "≥ 10× JADE"),
            new Case("many.jade.hops-per-s", "1,000 agents moving among 4 container JVMs, JADE (baseline): hops per second", true, null, List.of(), ""),
            new Case("many.robomw.p50", "1,000 agents, RoboMW: hop latency p50", false, "many.jade.p50", List.of(), ""),
            new Case("many.jade.p50", "1,000 agents, JADE: hop latency p50 (baseline)", false, null, List.of(), ""),
            new Case("many.robomw.p99", "1,000 agents, RoboMW: hop latency p99", false, "many.jade.p99", List.of(), "< 5,000 µs"),
            new Case("many.jade.p99", "1,000 agents, JADE: hop latency p99 (baseline)", false, null, List.of(), ""),
            new Case("many.robomw.cpu-per-hop", "1,000 agents, RoboMW: processor time of the 4 JVMs per hop", false, "many.jade.cpu-per-hop", List.of(), ""),
            new Case("many.jade.cpu-per-hop", "1,000 agents, JADE: processor time of the 4 JVMs per hop (baseline)", false, null, List.of(), ""),
            new Case("many.robomw.heap-per-parked", "1,000 agents waiting at one host, RoboMW: live heap per agent", false, "many.jade.heap-per-parked",
                    List.of(), "< JADE's"),
            new Case("many.jade.heap-per-parked", "1,000 agents waiting at one container, JADE: live heap per agent (baseline)", false, null, List.of(), ""),
            new Case("many.robomw.lost", "1,000 agents, RoboMW: agents not home at the end", false, null, List.of(), "0"),
            new Case("many.jade.lost", "1,000 agents, JADE: agents not home at the end", false, null, List.of(), ""),
            new Case("many.robomw.park-lost", "1,000 agents sent to wait at one host, RoboMW: agents that did not arrive", false, null, List.of(), "0"),
            new Case("many.jade.park-lost", "1,000 agents sent to wait at one container, JADE: agents that did not arrive", false, null, List.of(), ""),
            new Case("many.robomw.paced.p50", "1,000 agents paced at 50 % of RoboMW's saturated rate: hop latency p50", false, "many.jade.paced.p50", List.of(), ""),
            new Case("many.jade.paced.p50", "1,000 agents paced at 50 % of JADE's saturated rate: hop latency p50 (baseline)", false, null, List.of(), ""),
            new Case("many.robomw.paced.p99", "1,000 agents paced at 50 % of RoboMW's saturated rate: hop latency p99", false, "many.jade.paced.p99", List.of(), "< 5,000 µs"),
            new Case("many.jade.paced.p99", "1,000 agents paced at 50 % of JADE's saturated rate: hop latency p99 (baseline)", false, null, List.of(), ""),
            new Case("many.robomw.paced.hops-per-s", "1,000 agents paced, RoboMW: hops per second achieved", true, "many.jade.paced.hops-per-s", List.of(), ""),
            new Case("many.jade.paced.hops-per-s", "1,000 agents paced, JADE: hops per second achieved (baseline)", true, null, List.of(), ""),
            new Case("many.robomw.paced.wait", "1,000 agents paced, RoboMW: mean wait at each stop", false, null, List.of(), ""),
            new Case("many.jade.paced.wait", "1,000 agents paced, JADE: mean wait at each stop", false, null, List.of(), ""),
            // sensor-sized messages (issue 36): SensorBenchmark, SensorMqttBenchmark
            new Case("sensor.raw.100KB.1sub", "pub/sub 100 KB to 1 subscriber, plain sockets between the two JVMs (ceiling)", true, null, List.of(), ""),
            new Case("sensor.zmq.100KB.1sub", "pub/sub 100 KB to 1 subscriber, JeroMQ PUB/SUB (baseline)", true, null, List.of("sensor.raw.100KB.1sub"), ""),
            new Case("sensor.tcp.100KB.1sub", "pub/sub 100 KB to 1 subscriber, RoboMW tcp (shared memory on, the default)", true, "sensor.zmq.100KB.1sub",
                    List.of("sensor.raw.100KB.1sub", "ceiling.tcp-bulk"), "≥ 1.2× JeroMQ, ≥ 70 % of raw"),
            new Case("sensor.tcp-noshm.100KB.1sub", "pub/sub 100 KB to 1 subscriber, RoboMW tcp with shared memory off", true, "sensor.zmq.100KB.1sub",
                    List.of("sensor.raw.100KB.1sub", "ceiling.tcp-bulk"), ""),
            new Case("sensor.mqtt-mosquitto.bare.100KB.1sub", "MQTT (mosquitto) pub/sub 100 KB QoS 1 to 1 subscriber, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-mosquitto.robomw.100KB.1sub", "MQTT (mosquitto) pub/sub 100 KB QoS 1 to 1 subscriber, RoboMW", true, "sensor.mqtt-mosquitto.bare.100KB.1sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.mqtt-embedded.bare.100KB.1sub", "MQTT (embedded) pub/sub 100 KB QoS 1 to 1 subscriber, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-embedded.robomw.100KB.1sub", "MQTT (embedded) pub/sub 100 KB QoS 1 to 1 subscriber, RoboMW", true, "sensor.mqtt-embedded.bare.100KB.1sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.raw.100KB.8sub", "pub/sub 100 KB to 8 subscribers, plain sockets between the two JVMs (ceiling)", true, null, List.of(), ""),
            new Case("sensor.zmq.100KB.8sub", "pub/sub 100 KB to 8 subscribers, JeroMQ PUB/SUB (baseline)", true, null, List.of("sensor.raw.100KB.8sub"), ""),
            new Case("sensor.tcp.100KB.8sub", "pub/sub 100 KB to 8 subscribers, RoboMW tcp (shared memory on, the default)", true, "sensor.zmq.100KB.8sub",
                    List.of("sensor.raw.100KB.8sub", "ceiling.tcp-bulk"), "≥ 1.5× JeroMQ"),
            new Case("sensor.tcp-noshm.100KB.8sub", "pub/sub 100 KB to 8 subscribers, RoboMW tcp with shared memory off", true, "sensor.zmq.100KB.8sub",
                    List.of("sensor.raw.100KB.8sub", "ceiling.tcp-bulk"), ""),
            new Case("sensor.mqtt-mosquitto.bare.100KB.8sub", "MQTT (mosquitto) pub/sub 100 KB QoS 1 to 8 subscribers, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-mosquitto.robomw.100KB.8sub", "MQTT (mosquitto) pub/sub 100 KB QoS 1 to 8 subscribers, RoboMW", true, "sensor.mqtt-mosquitto.bare.100KB.8sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.mqtt-embedded.bare.100KB.8sub", "MQTT (embedded) pub/sub 100 KB QoS 1 to 8 subscribers, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-embedded.robomw.100KB.8sub", "MQTT (embedded) pub/sub 100 KB QoS 1 to 8 subscribers, RoboMW", true, "sensor.mqtt-embedded.bare.100KB.8sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.raw.1MiB.1sub", "pub/sub 1 MiB to 1 subscriber, plain sockets between the two JVMs (ceiling)", true, null, List.of(), ""),
            new Case("sensor.zmq.1MiB.1sub", "pub/sub 1 MiB to 1 subscriber, JeroMQ PUB/SUB (baseline)", true, null, List.of("sensor.raw.1MiB.1sub"), ""),
            new Case("sensor.tcp.1MiB.1sub", "pub/sub 1 MiB to 1 subscriber, RoboMW tcp (shared memory on, the default)", true, "sensor.zmq.1MiB.1sub",
                    List.of("sensor.raw.1MiB.1sub", "ceiling.tcp-bulk"), "≥ 1.2× JeroMQ, ≥ 70 % of raw"),
            new Case("sensor.tcp-noshm.1MiB.1sub", "pub/sub 1 MiB to 1 subscriber, RoboMW tcp with shared memory off", true, "sensor.zmq.1MiB.1sub",
                    List.of("sensor.raw.1MiB.1sub", "ceiling.tcp-bulk"), ""),
            new Case("sensor.mqtt-mosquitto.bare.1MiB.1sub", "MQTT (mosquitto) pub/sub 1 MiB QoS 1 to 1 subscriber, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-mosquitto.robomw.1MiB.1sub", "MQTT (mosquitto) pub/sub 1 MiB QoS 1 to 1 subscriber, RoboMW", true, "sensor.mqtt-mosquitto.bare.1MiB.1sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.mqtt-embedded.bare.1MiB.1sub", "MQTT (embedded) pub/sub 1 MiB QoS 1 to 1 subscriber, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-embedded.robomw.1MiB.1sub", "MQTT (embedded) pub/sub 1 MiB QoS 1 to 1 subscriber, RoboMW", true, "sensor.mqtt-embedded.bare.1MiB.1sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.raw.1MiB.8sub", "pub/sub 1 MiB to 8 subscribers, plain sockets between the two JVMs (ceiling)", true, null, List.of(), ""),
            new Case("sensor.zmq.1MiB.8sub", "pub/sub 1 MiB to 8 subscribers, JeroMQ PUB/SUB (baseline)", true, null, List.of("sensor.raw.1MiB.8sub"), ""),
            new Case("sensor.tcp.1MiB.8sub", "pub/sub 1 MiB to 8 subscribers, RoboMW tcp (shared memory on, the default)", true, "sensor.zmq.1MiB.8sub",
                    List.of("sensor.raw.1MiB.8sub", "ceiling.tcp-bulk"), "≥ 1.5× JeroMQ"),
            new Case("sensor.tcp-noshm.1MiB.8sub", "pub/sub 1 MiB to 8 subscribers, RoboMW tcp with shared memory off", true, "sensor.zmq.1MiB.8sub",
                    List.of("sensor.raw.1MiB.8sub", "ceiling.tcp-bulk"), ""),
            new Case("sensor.mqtt-mosquitto.bare.1MiB.8sub", "MQTT (mosquitto) pub/sub 1 MiB QoS 1 to 8 subscribers, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-mosquitto.robomw.1MiB.8sub", "MQTT (mosquitto) pub/sub 1 MiB QoS 1 to 8 subscribers, RoboMW", true, "sensor.mqtt-mosquitto.bare.1MiB.8sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            new Case("sensor.mqtt-embedded.bare.1MiB.8sub", "MQTT (embedded) pub/sub 1 MiB QoS 1 to 8 subscribers, bare HiveMQ client (baseline)", true, null, List.of(), ""),
            new Case("sensor.mqtt-embedded.robomw.1MiB.8sub", "MQTT (embedded) pub/sub 1 MiB QoS 1 to 8 subscribers, RoboMW", true, "sensor.mqtt-embedded.bare.1MiB.8sub",
                    List.of(), "overhead ≤ 10 % (≥ 0.91×)"),
            // MQTT
            new Case("mqtt.embedded.rr-bare", "MQTT request/reply 64 B QoS 1, bare HiveMQ client, embedded broker (baseline), p50", false, null,
                    List.of(), ""),
            new Case("mqtt.embedded.rr-robomw", "MQTT request/reply, RoboMW, embedded broker, p50", false, "mqtt.embedded.rr-bare", List.of(), ""),
            new Case("mqtt.embedded.ps-bare", "MQTT pub/sub 64 B QoS 1, bare HiveMQ client, embedded broker (baseline)", true, null, List.of(), ""),
            new Case("mqtt.embedded.ps-robomw", "MQTT pub/sub, RoboMW, embedded broker", true, "mqtt.embedded.ps-bare", List.of(), ""),
            new Case("mqtt.mosquitto.rr-bare", "MQTT request/reply, bare HiveMQ client, Mosquitto (baseline), p50", false, null, List.of(), ""),
            new Case("mqtt.mosquitto.rr-robomw", "MQTT request/reply, RoboMW, Mosquitto, p50", false, "mqtt.mosquitto.rr-bare", List.of(), ""),
            new Case("mqtt.mosquitto.ps-bare", "MQTT pub/sub, bare HiveMQ client, Mosquitto (baseline)", true, null, List.of(), ""),
            new Case("mqtt.mosquitto.ps-robomw", "MQTT pub/sub, RoboMW, Mosquitto", true, "mqtt.mosquitto.ps-bare", List.of(), ""),
            // NXT
            new Case("nxt.bare", "NXT GETINPUTVALUES round trip, bare write/read on a pty (baseline), p50", false, null, List.of(), ""),
            new Case("nxt.driver", "NXT GETINPUTVALUES round trip through the driver, p50", false, "nxt.bare", List.of(), "overhead ≤ 50 µs"),
            // rosbridge endpoint (issue 34): RosBridgeBenchmark
            new Case("rosbridge.odom100x50.rate", "rosbridge: odometry of 100 simulated robots at 50 Hz to one client, messages/s received", true, null,
                    List.of(), "5000 (every one)"),
            new Case("rosbridge.odom100x50.endpoint-cpu-per-msg", "rosbridge: the endpoint's threads' CPU per odometry message", false, null, List.of(), ""),
            new Case("rosbridge.odom100x50.jvm-cpu-per-msg", "rosbridge: the server JVM's CPU per odometry message over the world alone", false, null,
                    List.of(), ""),
            new Case("rosbridge.odom100x50.world-alone-cpu", "rosbridge: the 100-robot world alone, before the client subscribed (baseline)", false, null,
                    List.of(), ""),
            new Case("rosbridge.rtt64.echo.p50", "plain WebSocket echo, 64 B, on the endpoint's server (baseline), p50", false, null, List.of(), ""),
            new Case("rosbridge.rtt64.publish.p50", "rosbridge: 64-byte publish round trip (publish, get it back as a subscriber), p50", false,
                    "rosbridge.rtt64.echo.p50", List.of(), ""),
            new Case("rosbridge.rtt64.echo.p99", "plain WebSocket echo, 64 B (baseline), p99", false, null, List.of(), ""),
            new Case("rosbridge.rtt64.publish.p99", "rosbridge: 64-byte publish round trip, p99", false, "rosbridge.rtt64.echo.p99", List.of(), ""));

    private BenchReport() {
    }

    /**
     * @param args the samples file, the machine description (markdown), the output file
     * @throws IOException if a file cannot be read or written
     */
    public static void main(String[] args) throws IOException {
        Map<String, List<Double>> values = new LinkedHashMap<>();
        Map<String, String> units = new LinkedHashMap<>();
        Map<String, Map<String, Double>> byRound = new LinkedHashMap<>();
        for (String l : Files.readAllLines(Path.of(args[0]), StandardCharsets.UTF_8)) {
            String[] f = l.trim().split("\\s+");
            // sample-number BENCH id value unit
            if (f.length < 5 || !f[1].equals("BENCH")) {
                continue;
            }
            double v;
            try {
                v = Double.parseDouble(f[3]);
            } catch (NumberFormatException e) {
                continue;
            }
            values.computeIfAbsent(f[2], k -> new ArrayList<>()).add(v);
            byRound.computeIfAbsent(f[2], k -> new LinkedHashMap<>()).put(f[0], v);
            units.put(f[2], f[4]);
        }
        StringBuilder md = new StringBuilder();
        md.append(Files.readString(Path.of(args[1]), StandardCharsets.UTF_8)).append('\n');
        md.append("| case | runs | median | min | max | unit | ratio of medians to the baseline (> 1: RoboMW better; per round: each round's sample against the baseline's) | ceiling, same run (median) | target |\n");
        md.append("|---|---:|---:|---:|---:|---|---:|---|---|\n");
        Map<String, Case> known = new LinkedHashMap<>();
        CATALOGUE.forEach(c -> known.put(c.id(), c));
        List<String> order = new ArrayList<>();
        CATALOGUE.stream().map(Case::id).filter(values::containsKey).forEach(order::add);
        values.keySet().stream().filter(k -> !known.containsKey(k)).forEach(order::add);
        for (String id : order) {
            Case c = known.getOrDefault(id, new Case(id, id, true, null, List.of(), ""));
            double[] v = values.get(id).stream().mapToDouble(Double::doubleValue).sorted().toArray();
            double median = median(v);
            String ratio = "";
            if (c.baseline() != null && values.containsKey(c.baseline())) {
                double b = median(values.get(c.baseline()).stream().mapToDouble(Double::doubleValue).sorted().toArray());
                ratio = String.format(Locale.ROOT, "%.2f× %s", c.higher() ? median / b : b / median, shortName(c.baseline()))
                        + roundRatios(byRound.get(id), byRound.get(c.baseline()), c.higher());
            }
            StringBuilder ceiling = new StringBuilder();
            for (String cid : c.ceiling()) {
                if (values.containsKey(cid)) {
                    double cm = median(values.get(cid).stream().mapToDouble(Double::doubleValue).sorted().toArray());
                    ceiling.append(ceiling.length() == 0 ? "" : "; ").append(shortName(cid)).append(' ').append(format(cm)).append(' ').append(units.get(cid));
                    if (units.get(cid).equals(units.get(id))) {
                        ceiling.append(String.format(Locale.ROOT, " (%.0f %% of it)", 100 * (c.higher() ? median / cm : cm / median)));
                    }
                }
            }
            md.append(String.format(Locale.ROOT, "| %s (`%s`) | %d | %s | %s | %s | %s | %s | %s | %s |%n", c.label(), id, v.length, format(median),
                    format(v[0]), format(v[v.length - 1]), units.get(id), ratio, ceiling, c.target()));
        }
        md.append("\nEvery sample (in run order):\n\n");
        for (String id : order) {
            md.append("- `").append(id).append("`: ");
            List<String> each = new ArrayList<>();
            values.get(id).forEach(x -> each.add(format(x)));
            md.append(String.join(", ", each)).append(' ').append(units.get(id)).append('\n');
        }
        Path out = Path.of(args[2]);
        if (out.getParent() != null) {
            Files.createDirectories(out.getParent());
        }
        Files.writeString(out, md.toString(), StandardCharsets.UTF_8);
        System.out.println(md);
    }

    /**
     * The spread of the ratio: each round's sample against the baseline's sample of the same round
     * (both in that round's fresh JVMs, one after the other).
     *
     * @return {@code " (per round: median M, min-max A-B)"}, or nothing with fewer than two rounds in common
     */
    static String roundRatios(Map<String, Double> samples, Map<String, Double> baseline, boolean higher) {
        List<Double> r = new ArrayList<>();
        samples.forEach((round, v) -> {
            Double b = baseline.get(round);
            if (b != null && v != 0 && b != 0) {
                r.add(higher ? v / b : b / v);
            }
        });
        if (r.size() < 2) {
            return "";
        }
        double[] sorted = r.stream().mapToDouble(Double::doubleValue).sorted().toArray();
        return String.format(Locale.ROOT, " (per round: median %.2f×, %.2f-%.2f)", median(sorted), sorted[0], sorted[sorted.length - 1]);
    }

    private static String shortName(String id) {
        return id.substring(id.indexOf('.') + 1);
    }

    static double median(double[] sorted) {
        int n = sorted.length;
        return n % 2 == 1 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
    }

    private static String format(double v) {
        double a = Math.abs(v);
        if (a >= 10_000) {
            return String.format(Locale.ROOT, "%,.0f", v);
        }
        if (a >= 100) {
            return String.format(Locale.ROOT, "%.0f", v);
        }
        if (a >= 10) {
            return String.format(Locale.ROOT, "%.1f", v);
        }
        return String.format(Locale.ROOT, "%.2f", v);
    }
}
