package io.robomw.bench.jade;

import jade.core.Profile;
import jade.core.ProfileImpl;
import jade.core.Runtime;
import jade.wrapper.AgentContainer;

import java.io.BufferedReader;
import java.io.FileDescriptor;
import java.io.FileOutputStream;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;
import java.util.logging.Handler;
import java.util.logging.Level;
import java.util.logging.LogManager;
import java.util.logging.Logger;

/**
 * One JADE container in its own JVM, for {@link JadeMoveBaseline}: the main container (A, where
 * the timed agent lives) or a peripheral container (B, which the agent visits). Everything is on
 * loopback: the container binds its JICP server to 127.0.0.1 only and announces 127.0.0.1, no
 * message transport protocol (HTTP MTP) is started, no multicast main-container detection, no
 * GUI.
 *
 * <p>Arguments: {@code main NAME PORT} or {@code peripheral NAME MAIN_PORT LOCAL_PORT}.
 * Stdout carries only the protocol (whatever JADE itself prints goes to stderr, the log):
 * {@code READY NAME} once the container has joined the platform; on the main container the
 * command {@code MEASURE PAYLOAD WARMUP ITERATIONS DESTINATION IDLE_SECONDS} answers
 * {@code RESULT PAYLOAD n1,n2,...} (round trips in nanoseconds) or {@code ERR message}. The
 * JVM ends when stdin closes.
 */
public final class JadeContainerMain {

    /** Agent mobility on, and the notification service JADE starts by default next to it. */
    static final String SERVICES = "jade.core.mobility.AgentMobilityService;jade.core.event.NotificationService";
    static final String LOOPBACK = "127.0.0.1";

    private JadeContainerMain() {
    }

    /**
     * @param args see the class comment
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        PrintStream out = new PrintStream(new FileOutputStream(FileDescriptor.out), true, StandardCharsets.UTF_8);
        System.setOut(System.err);
        quietLogging();

        boolean main = args[0].equals("main");
        String name = args[1];
        int platformPort = Integer.parseInt(args[2]);
        int localPort = main ? platformPort : Integer.parseInt(args[3]);

        AgentContainer container = startContainer(main, name, platformPort, localPort);
        if (container == null) {
            out.println("ERR container " + name + " did not start (see its log)");
            System.exit(1);
        }
        out.println("READY " + container.getContainerName());

        ExecutorService worker = Executors.newSingleThreadExecutor(r -> {
            Thread t = new Thread(r, "jade-bench-command");
            t.setDaemon(true);
            return t;
        });
        int[] agents = {0};
        try (BufferedReader in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8))) {
            String line;
            while ((line = in.readLine()) != null) {
                String[] c = line.trim().split(" ");
                if (c[0].equals("MEASURE")) {
                    String agent = "mover-" + ++agents[0];
                    worker.execute(() -> out.println(measure(container, agent, c)));
                } else if (c[0].equals("exit")) {
                    break;
                } else if (!c[0].isEmpty()) {
                    out.println("ERR unknown command " + line);
                }
            }
        } catch (IOException driverGone) {
            // the driver is gone: end as on exit
        }
        shutdown(container, worker);
    }

    /**
     * Starts this JVM's container on loopback (see the class comment).
     *
     * @param main         whether it is the main container
     * @param name         its name
     * @param platformPort the main container's port
     * @param localPort    this container's port (the main container's: {@code platformPort})
     * @return the container, or {@code null} if JADE could not start it
     */
    public static AgentContainer startContainer(boolean main, String name, int platformPort, int localPort) {
        // The same as the command line -host 127.0.0.1 -port P -local-host 127.0.0.1 -local-port Q
        // -nomtp -services ..., plus two things -local-host does not do: bind the JICP server
        // socket to local-host only (JADE binds it to the wildcard address otherwise), and no
        // main-container detection (on by default in a main container: a MulticastSocket on the
        // wildcard address, port 1199, joined to 239.255.10.99 on the default interface).
        jade.util.leap.Properties p = new jade.util.leap.Properties();
        p.setProperty(Profile.MAIN, String.valueOf(main));
        p.setProperty(Profile.MAIN_HOST, LOOPBACK);
        p.setProperty(Profile.MAIN_PORT, String.valueOf(platformPort));
        p.setProperty(Profile.LOCAL_HOST, LOOPBACK);
        p.setProperty(Profile.LOCAL_PORT, String.valueOf(localPort));
        p.setProperty(Profile.NO_MTP, "true");
        p.setProperty(Profile.GUI, "false");
        p.setProperty(Profile.SERVICES, SERVICES);
        p.setProperty(Profile.CONTAINER_NAME, name);
        p.setProperty(Profile.PLATFORM_ID, "robomw-jade-bench");
        p.setProperty("jade_imtp_leap_JICP_JICPServer_acceptlocalhostonly", "true");
        p.setProperty("detect-main", "false");

        Runtime runtime = Runtime.instance();
        runtime.setCloseVM(false);
        Profile profile = new ProfileImpl(p);
        return main ? runtime.createMainContainer(profile) : runtime.createAgentContainer(profile);
    }

    private static String measure(AgentContainer container, String agent, String[] c) {
        try {
            int payload = Integer.parseInt(c[1]);
            int warmup = Integer.parseInt(c[2]);
            int iterations = Integer.parseInt(c[3]);
            String destination = c[4];
            Duration idle = Duration.ofSeconds(Long.parseLong(c[5]));
            JadeRoundTripLog.Run run = JadeRoundTripLog.begin(agent, payload, warmup, iterations);
            container.createNewAgent(agent, JadeMoverAgent.class.getName(), new Object[] {payload, destination}).start();
            long[] nanos = run.await(idle);
            StringBuilder sb = new StringBuilder(20 + nanos.length * 9).append("RESULT ").append(payload).append(' ');
            for (int i = 0; i < nanos.length; i++) {
                sb.append(i == 0 ? "" : ",").append(nanos[i]);
            }
            return sb.toString();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return "ERR interrupted";
        } catch (Exception e) {
            e.printStackTrace();
            return ("ERR " + e).replace('\n', ' ');
        }
    }

    /** Kills the container (a peripheral one leaves the platform; the main one ends it), then the JVM, in 5 s at most. */
    private static void shutdown(AgentContainer container, ExecutorService worker) throws InterruptedException {
        worker.shutdownNow();
        Thread killer = new Thread(() -> {
            try {
                container.kill();
            } catch (Exception e) {
                System.err.println("kill: " + e);
            }
        }, "jade-bench-kill");
        killer.setDaemon(true);
        killer.start();
        killer.join(TimeUnit.SECONDS.toMillis(5));
        System.exit(0);
    }

    /** JADE logs through java.util.logging: only warnings and worse, on stderr. */
    public static void quietLogging() {
        Logger root = LogManager.getLogManager().getLogger("");
        root.setLevel(Level.WARNING);
        for (Handler h : root.getHandlers()) {
            h.setLevel(Level.WARNING);
        }
    }
}
