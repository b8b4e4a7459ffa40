package io.robomw.bench.many;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import io.robomw.bench.AgentBenchPeer;
import io.robomw.bench.jade.JadeContainerMain;
import io.robomw.bench.jade.JadeHopperAgent;
import io.robomw.bench.jade.JadeParkedAgent;
import jade.wrapper.AgentContainer;

import java.io.BufferedReader;
import java.io.FileDescriptor;
import java.io.FileOutputStream;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.lang.management.ManagementFactory;
import java.net.URL;
import java.net.URLClassLoader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * One host JVM of {@link ManyAgentsBenchmark}: a RoboMW agent host ({@code robomw NAME}) or a JADE
 * container ({@code jade main NAME PORT} or {@code jade peripheral NAME MAIN_PORT LOCAL_PORT}), on
 * 127.0.0.1. Stdout carries only the protocol; one answer per command:
 *
 * <ul>
 *   <li>{@code READY address-or-container} once it listens.</li>
 *   <li>{@code LAUNCH N JAR ADDR...} (RoboMW; JAR holds the agent's class, which only this JVM gets)
 *   or {@code LAUNCH N CONTAINER...} (JADE): starts N hopping agents whose home is this host;
 *   {@code LAUNCHED N}.</li>
 *   <li>{@code MEASURE}: empties the histogram and records; {@code MEASURING}.</li>
 *   <li>{@code SNAP}: stops recording; {@code SNAP bucket:count,...}.</li>
 *   <li>{@code PACE NANOS}: hopping agents wait NANOS on average at each stop from now on (0:
 *   not at all); {@code PACED}.</li>
 *   <li>{@code STOP}: agents go home at their next stop; {@code STOPPING}.</li>
 *   <li>{@code HOME}: {@code HOME n failed} (agents home, trips that failed).</li>
 *   <li>{@code PARK N JAR TARGET} (RoboMW) or {@code PARK N TARGET} (JADE): sends N agents to wait at
 *   TARGET; {@code PARKING N}. {@code PARKED}: {@code PARKED n} waiting here. {@code RELEASE}: lets
 *   RoboMW's end (JADE's stay, idle); {@code RELEASED}. {@code RETURNED}: {@code RETURNED n}, the
 *   parked agents sent from here whose trips have ended.</li>
 *   <li>{@code HEAP}: {@code HEAP bytes}, the heap in use after two full collections.</li>
 * </ul>
 */
public final class ManyAgentsPeer {

    static final ClusterKey KEY = ClusterKey.fromPassphrase("robomw many-agents benchmark");
    static final String AGENT_CLASS = "io.robomw.benchagent.HopAgent";

    private final PrintStream out;
    private final HopLog log = HopLog.install();
    private final AtomicInteger failed = new AtomicInteger();
    /** RoboMW's parked agents whose trips ended (released) with the result expected. */
    private final AtomicInteger parkedReturned = new AtomicInteger();
    private final List<URLClassLoader> loaders = new ArrayList<>();
    private AgentHost host;
    private AgentContainer container;
    /** JADE: the parked agents made so far ({@code parked-0}, {@code parked-1}, ...). */
    private int parkedNames;

    private ManyAgentsPeer(PrintStream out) {
        this.out = out;
    }

    /**
     * @param args see the class comment
     * @throws Exception if the host cannot start
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(new FileOutputStream(FileDescriptor.out), true, StandardCharsets.UTF_8);
        System.setOut(System.err);
        ManyAgentsPeer peer = new ManyAgentsPeer(out);
        if (args[0].equals("robomw")) {
            peer.host = AgentBenchPeer.spin(AgentHost.builder(args[1]).bind("127.0.0.1").clusterKey(KEY)).start();
            out.println("READY " + peer.host.address());
        } else {
            JadeContainerMain.quietLogging();
            boolean main = args[1].equals("main");
            int platformPort = Integer.parseInt(args[3]);
            peer.container = JadeContainerMain.startContainer(main, args[2], platformPort, main ? platformPort : Integer.parseInt(args[4]));
            if (peer.container == null) {
                out.println("ERR container " + args[2] + " did not start (see its log)");
                System.exit(1);
            }
            out.println("READY " + peer.container.getContainerName());
        }
        try (BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8))) {
            for (String line; (line = in.readLine()) != null && !line.equals("exit"); ) {
                try {
                    out.println(peer.command(line.trim().split(" ")));
                } catch (Exception e) {
                    e.printStackTrace();
                    out.println(("ERR " + e).replace('\n', ' '));
                }
            }
        }
        peer.close();
        System.exit(0);
    }

    private String command(String[] c) throws Exception {
        return switch (c[0]) {
            case "LAUNCH" -> launch(Integer.parseInt(c[1]), c);
            case "MEASURE" -> {
                log.measure();
                yield "MEASURING";
            }
            case "SNAP" -> "SNAP " + log.snapshot();
            case "PACE" -> {
                HopLog.pace(Long.parseLong(c[1]));
                yield "PACED";
            }
            case "STOP" -> {
                log.stop();
                yield "STOPPING";
            }
            case "HOME" -> "HOME " + HopLog.counter(HopLog.HOME).get() + " " + failed.get();
            case "PARK" -> park(Integer.parseInt(c[1]), c);
            case "PARKED" -> "PARKED " + HopLog.counter(HopLog.PARKED).get();
            case "RETURNED" -> "RETURNED " + parkedReturned.get();
            case "RELEASE" -> release();
            case "HEAP" -> "HEAP " + liveHeap();
            default -> "ERR unknown command " + String.join(" ", c);
        };
    }

    private String launch(int n, String[] c) throws Exception {
        if (host != null) {
            String[] hosts = java.util.Arrays.copyOfRange(c, 3, c.length);
            Class<?> agentClass = loader(c[2]).loadClass(AGENT_CLASS);
            java.lang.reflect.Constructor<?> make = agentClass.getConstructor(String[].class, long.class, boolean.class);
            for (int i = 0; i < n; i++) {
                Agent agent = (Agent) make.newInstance(hosts, 0x9E3779B97F4A7C15L * (i + 1), false);
                agent.itinerary().addStop(host.address());
                follow(host.agency().startTrip(agent), "home");
            }
        } else {
            String[] containers = java.util.Arrays.copyOfRange(c, 2, c.length);
            for (int i = 0; i < n; i++) {
                container.createNewAgent("hopper-" + i, JadeHopperAgent.class.getName(), new Object[] {containers, 0x9E3779B97F4A7C15L * (i + 1)}).start();
            }
        }
        return "LAUNCHED " + n;
    }

    private String park(int n, String[] c) throws Exception {
        if (host != null) {
            Class<?> agentClass = loader(c[2]).loadClass(AGENT_CLASS);
            java.lang.reflect.Constructor<?> make = agentClass.getConstructor(String[].class, long.class, boolean.class);
            for (int i = 0; i < n; i++) {
                Agent agent = (Agent) make.newInstance(new String[] {c[3]}, 1L, true);
                agent.itinerary().addStop(c[3]);
                follow(host.agency().startTrip(agent), "parked");
            }
        } else {
            for (int i = 0; i < n; i++) {
                container.createNewAgent("parked-" + parkedNames++, JadeParkedAgent.class.getName(), new Object[] {c[2]}).start();
            }
        }
        return "PARKING " + n;
    }

    /**
     * Lets RoboMW's agents waiting here end (their stop's work returns; their trips end here).
     * JADE's stay, idle (a thread each, blocked): killing a thousand JADE agents one by one took
     * more than 2 minutes on a loaded machine, and an idle JADE agent takes no processor time.
     */
    private String release() {
        ((CountDownLatch) System.getProperties().get(HopLog.GATE)).countDown();
        return "RELEASED";
    }

    /** Counts the agent home when its trip ends with the result expected, as failed otherwise. */
    private void follow(AgentRef ref, String expected) {
        ref.result().whenComplete((r, e) -> {
            if (e == null && expected.equals(r)) {
                if (expected.equals("home")) {
                    HopLog.counter(HopLog.HOME).incrementAndGet();
                } else {
                    parkedReturned.incrementAndGet();
                }
            } else {
                failed.incrementAndGet();
                System.err.println("trip ended with " + (e != null ? e : r));
            }
        });
    }

    private URLClassLoader loader(String jar) throws Exception {
        URLClassLoader l = new URLClassLoader("many-agents", new URL[] {Path.of(jar).toUri().toURL()}, ManyAgentsPeer.class.getClassLoader());
        loaders.add(l);
        return l;
    }

    /** @return the heap in use after two full collections: the live objects */
    static long liveHeap() {
        System.gc();
        System.gc();
        return ManagementFactory.getMemoryMXBean().getHeapMemoryUsage().getUsed();
    }

    private void close() throws Exception {
        ((CountDownLatch) System.getProperties().get(HopLog.GATE)).countDown();
        if (host != null) {
            host.close();
        }
        if (container != null) {
            Thread killer = new Thread(() -> {
                try {
                    container.kill();
                } catch (Exception e) {
                    System.err.println("kill: " + e);
                }
            }, "jade-many-kill");
            killer.setDaemon(true);
            killer.start();
            killer.join(5000);
        }
        for (URLClassLoader l : loaders) {
            l.close();
        }
    }
}
