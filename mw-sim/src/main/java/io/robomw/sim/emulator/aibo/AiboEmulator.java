package io.robomw.sim.emulator.aibo;

import io.robomw.sim.SimRobot;
import io.robomw.sim.Simulation;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.sim.emulator.Acceptor;
import io.robomw.sim.emulator.Emulator;
import io.robomw.sim.emulator.EmulatorThreads;
import io.robomw.sim.legged.UrbiKernel;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.nio.charset.StandardCharsets;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A virtual Sony Aibo: an URBI 1.x server on TCP (port 54000 like the dog's own) whose dog is a
 * simulated quadruped of the world ({@link io.robomw.sim.legged.Quadruped}, its server core
 * {@link UrbiKernel}). Clients connect as they would to the dog over wireless LAN; the real
 * {@code platform: aibo} driver walks the simulated dog byte for byte.
 *
 * <h2>Sessions</h2>
 * Up to {@value #MAX_CLIENTS} clients at once, each greeted with the server's banner (untagged
 * {@code ***} lines). Each has a reader thread ({@code emulator-aibo-<robot>-N}) that cuts and
 * parses what it sends and queues it for the dog, and a writer thread ({@code ...-N-out}) that
 * sends the server's messages, {@code [timestamp:tag] payload}, the timestamp in milliseconds of
 * simulated time since the emulator was bound. A client that leaves (or whose link is cut) has
 * every command it started stopped at the next world step: the dog stands still. A client that
 * does not read its messages fast enough ({@value #OUTBOX} waiting) is disconnected.
 *
 * <h2>Bad input</h2>
 * A line that is not URBI, an unknown device or function, a speed above the gait's limits:
 * each gets its {@code !!!} message (tagged when its tag could be read) and the session goes on.
 *
 * <h2>Failures</h2>
 * The accepting thread ({@code emulator-aibo-<robot>}, an {@link io.robomw.api.spi.OwnerThread})
 * and each client's reader and writer hand what they catch to the simulation's
 * {@link FailurePolicy}: a failed accept is reported and the next client accepted; whatever ends a
 * client's reader or writer other than its connection closing is reported, and that client is
 * disconnected (its commands stop), the others served on. A client's reader waits at most half a
 * second in one read before it looks whether its client was disconnected.
 */
public final class AiboEmulator implements Emulator {

    private static final Logger LOG = LoggerFactory.getLogger(AiboEmulator.class);
    /** One line a second at most about refused clients: a flood of connections must not flood the log. */
    private final io.robomw.platform.ThrottledWarnings refusedWarnings = new io.robomw.platform.ThrottledWarnings(LOG, java.time.Duration.ofSeconds(1), io.robomw.api.Clock.system());

    /** Clients served at once. */
    public static final int MAX_CLIENTS = 8;
    /** Messages that may wait for a client. */
    public static final int OUTBOX = 8192;
    /** The longest one read of a client waits before its reader looks whether the client was disconnected, milliseconds. */
    private static final int READ_POLL_MILLIS = 500;
    /** The banner, one {@code ***} line each. */
    static final List<String> BANNER = List.of(
            "********************************************************",
            "URBI Language specif 1.0 - Copyright 2005 Gostai SAS",
            "URBI Kernel version 1.x, emulated by RoboMW",
            "Simulated Aibo ERS-7: robot.walk, robot.turn, robot.arc, robot.drive, robot.stop,",
            "robot.sit, robot.stand, robot.lie, robot.kick; devices by their Aibo names",
            "********************************************************");

    private final SimRobot robot;
    private final UrbiKernel kernel;
    private final FailurePolicy failures;
    private final List<Client> clients = new CopyOnWriteArrayList<>();
    private final List<Runnable> closeActions = new CopyOnWriteArrayList<>();
    private final AtomicLong connections = new AtomicLong();
    private final AtomicLong bytesIn = new AtomicLong();
    private final Runnable stepListener = this::onStep;
    private volatile ServerSocket server;
    private volatile boolean closed;
    private boolean halted;
    private io.robomw.api.spi.OwnerThread acceptor;

    private AiboEmulator(SimRobot robot, FailurePolicy failures) {
        this.robot = robot;
        this.kernel = robot.kernel();
        this.failures = failures;
    }

    /**
     * Binds an emulator to a legged robot of a simulation and steps it with the world.
     *
     * @param simulation the simulation (the robot should be one it emulates, see
     *                   {@code Simulation.load(world, names)})
     * @param robotName  the robot
     * @return the emulator, not yet serving: call {@link #startOnTcp}; closing it also unbinds it
     * @throws IllegalArgumentException if the world has no such robot, or it has no legged drive
     */
    public static AiboEmulator bind(Simulation simulation, String robotName) {
        SimRobot r = simulation.world().robot(robotName);
        if (r == null) {
            throw new IllegalArgumentException("world '" + simulation.world().description().name() + "' has no robot '" + robotName + "'");
        }
        if (r.quadruped() == null) {
            throw new IllegalArgumentException("robot '" + robotName + "' (" + r.description().source()
                    + ") has no legged drive (drive: {type: legged}); the Aibo emulator drives a simulated quadruped");
        }
        AiboEmulator e = new AiboEmulator(r, simulation.failures());
        simulation.addStepListener(e.stepListener);
        e.closeActions.add(() -> simulation.removeStepListener(e.stepListener));
        return e;
    }

    /** @return the listener the simulation runs after every step; always the same one */
    public Runnable stepListener() {
        return stepListener;
    }

    private void onStep() {
        if (closed && !halted) {
            halted = true;
            robot.quadruped().stop();
            for (Runnable action : closeActions) {
                action.run();
            }
            closeActions.clear();
        }
    }

    /** URBI runs over TCP only. */
    @Override
    public String startOnPseudoTerminal() throws IOException {
        throw new IOException("the Aibo's URBI server runs on TCP only; use --tcp (its port is 54000)");
    }

    @Override
    public synchronized int startOnTcp(String bindAddress, int port) throws IOException {
        if (server != null) {
            throw new IllegalStateException("the Aibo emulator of '" + robot.name() + "' already serves on " + describe());
        }
        ServerSocket s = new ServerSocket();
        try {
            s.setReuseAddress(true);
            s.bind(new InetSocketAddress(bindAddress, port), MAX_CLIENTS);
        } catch (IOException e) {
            s.close();
            throw new IOException("cannot listen on " + bindAddress + ":" + port + ": " + e.getMessage(), e);
        }
        try {
            acceptor = Acceptor.start("emulator-aibo-" + robot.name(), s, this::accepted, failures);
        } catch (IOException e) {
            s.close();
            throw e;
        }
        server = s;
        LOG.info("aibo emulator for '{}' serving URBI on {}", robot.name(), describe());
        return s.getLocalPort();
    }

    /** A client connected: served if there is room, else refused. On the accepting thread. */
    private void accepted(Socket socket) throws IOException {
        if (clients.size() >= MAX_CLIENTS) {
            refusedWarnings.warn("aibo emulator for '{}': refused {}: {} clients already", robot.name(), socket.getRemoteSocketAddress(), MAX_CLIENTS);
            quietly(socket);
            return;
        }
        socket.setTcpNoDelay(true);
        Client c = new Client(socket, connections.incrementAndGet());
        clients.add(c);
        c.start();
    }

    /** @return clients connected now */
    public int clientCount() {
        return clients.size();
    }

    /** @return bytes received from every client since it started */
    public long bytesReceived() {
        return bytesIn.get();
    }

    /** @return clients served since it started */
    public long connectionsServed() {
        return connections.get();
    }

    /** Cuts every client's connection, as a lost wireless link does; the dog stops at the next step. */
    public void dropClients() {
        for (Client c : clients) {
            c.close();
        }
    }

    @Override
    public String describe() {
        ServerSocket s = server;
        return s == null ? "aibo emulator (not serving)" : "aibo emulator on tcp " + s.getInetAddress().getHostAddress() + ":" + s.getLocalPort();
    }

    /** Stops serving and disconnects every client; at the next world step the dog stops and it unbinds. */
    @Override
    public synchronized void close() {
        closed = true;
        ServerSocket s = server;
        if (s != null) {
            quietly(s);
        }
        for (Client c : clients) {
            c.close();
        }
        if (acceptor != null) {
            acceptor.close();
        }
    }

    private static void quietly(AutoCloseable c) {
        try {
            c.close();
        } catch (Exception e) {
            LOG.debug("closing {}: {}", c, e.toString());
        }
    }

    /** One client: its session with the dog, its reader and its writer. */
    private final class Client {
        private final Socket socket;
        private final long number;
        private final BlockingQueue<byte[]> outbox = new ArrayBlockingQueue<>(OUTBOX);
        private final UrbiKernel.Session session;
        private final String name;
        private volatile boolean open = true;

        Client(Socket socket, long number) {
            this.socket = socket;
            this.number = number;
            this.name = "client " + number + " (" + socket.getRemoteSocketAddress() + ")";
            for (String line : BANNER) {
                outbox.add(line(kernel.millis(), "", UrbiKernel.Kind.SYSTEM, line));
            }
            this.session = kernel.open(name, (millis, tag, kind, text) -> send(line(millis, tag, kind, text)));
        }

        void start() {
            Thread reader = new Thread(this::read, "emulator-aibo-" + robot.name() + "-" + number);
            Thread writer = new Thread(this::write, "emulator-aibo-" + robot.name() + "-" + number + "-out");
            reader.setDaemon(true);
            writer.setDaemon(true);
            reader.start();
            writer.start();
            LOG.info("aibo emulator for '{}': {} connected", robot.name(), name);
        }

        private void send(byte[] line) {
            if (open && !outbox.offer(line)) {
                LOG.warn("aibo emulator for '{}': {} does not read its messages ({} waiting); disconnected", robot.name(), name, OUTBOX);
                close();
            }
        }

        /** The client's reader: until its connection closes; any other end is reported, and it is disconnected. */
        private void read() {
            byte[] buf = new byte[4096];
            try (InputStream in = socket.getInputStream()) {
                socket.setSoTimeout(READ_POLL_MILLIS);
                while (open) {
                    int n;
                    try {
                        n = in.read(buf);
                    } catch (SocketTimeoutException e) {
                        continue; // nothing for a while: look whether the client was disconnected, and read on
                    }
                    if (n < 0) {
                        break;
                    }
                    bytesIn.addAndGet(n);
                    session.submit(buf, 0, n);
                }
            } catch (IOException e) {
                if (open) {
                    LOG.debug("aibo emulator for '{}': {}: {}", robot.name(), name, e.toString());
                }
            } catch (Throwable t) {
                EmulatorThreads.ended(failures, Thread.currentThread().getName(), t);
            } finally {
                close();
            }
        }

        /** The client's writer: until its connection closes and its messages are sent; any other end is reported, and it is disconnected. */
        private void write() {
            try (OutputStream out = socket.getOutputStream()) {
                while (open || !outbox.isEmpty()) {
                    byte[] next = outbox.poll(100, TimeUnit.MILLISECONDS);
                    if (next != null) {
                        out.write(next);
                        if (outbox.isEmpty()) {
                            out.flush();
                        }
                    }
                }
            } catch (IOException e) {
                LOG.debug("aibo emulator for '{}': writing to {}: {}", robot.name(), name, e.toString());
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            } catch (Throwable t) {
                EmulatorThreads.ended(failures, Thread.currentThread().getName(), t);
            } finally {
                close();
            }
        }

        void close() {
            if (!open) {
                return;
            }
            open = false;
            session.close();
            clients.remove(this);
            quietly(socket);
            LOG.info("aibo emulator for '{}': {} left; its commands stop", robot.name(), name);
        }
    }

    /**
     * @param millis the server's clock
     * @param tag    the tag, or ""
     * @param kind   what it is
     * @param text   the payload
     * @return the message as the server writes it: {@code [00001234:tag] payload} and a newline (a
     *         line break in the payload becomes a space)
     */
    public static byte[] line(long millis, String tag, UrbiKernel.Kind kind, String text) {
        String payload = switch (kind) {
            case SYSTEM -> "*** " + text;
            case ERROR -> "!!! " + text;
            case VALUE -> text;
        };
        String clean = payload.replace('\n', ' ').replace('\r', ' ');
        return String.format(Locale.ROOT, "[%08d%s] %s\n", millis, tag.isEmpty() ? "" : ":" + tag, clean).getBytes(StandardCharsets.UTF_8);
    }
}
