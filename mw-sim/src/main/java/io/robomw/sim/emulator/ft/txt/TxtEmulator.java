package io.robomw.sim.emulator.ft.txt;

import io.robomw.api.SensorType;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.ft.txt.TxtPorts;
import io.robomw.platform.ft.txt.TxtProtocol;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.LinkModel;
import io.robomw.sim.emulator.Framing;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * A virtual fischertechnik TXT in online mode: answers the messages of {@link TxtProtocol}'s table
 * (queryStatus, startOnline, updateConfig, the simple exchange, stopOnline) exactly by id and
 * size, on TCP, with its motors and inputs bound to a robot in a simulated world. Input is framed
 * by the message id: the 4-byte id, then the rest of that request's fixed size; an id that is not
 * in the table is dropped (the compressed exchange, camera and I²C messages are not emulated).
 *
 * <h2>Firmware model</h2>
 * <ul>
 *   <li><b>Motors</b> M1..M4 of the description turn at (pwm[2i] − pwm[2i+1]) ÷ 512 ×
 *   {@link FtMotors#DEGREES_PER_SECOND_AT_FULL_POWER} degrees per second, when updateConfig made
 *   the output a motor (the default).</li>
 *   <li><b>Counters</b> C1..C4 count the encoder pulses of the wheel wired to them
 *   ({@link TxtPorts#wheelCounters}): |rotation| × {@code encoder_ticks_per_revolution} ÷ 360,
 *   upwards whichever way the wheel turns, from the simulated wheel's rotation. A changed
 *   counter_cmd_id resets the counter to 0 and is echoed.</li>
 *   <li><b>Distance commands:</b> a changed motor_cmd_id with motor_dist N &gt; 0 runs motor Mi until
 *   counter Ci has counted N more pulses, stops it (until its PWM or command changes) and then echoes
 *   the id; with N = 0 the id is echoed at once and the motor runs without a limit. motor_sync is
 *   accepted; simulated motors given the same PWM turn alike, so there is nothing to correct.</li>
 *   <li><b>Inputs</b> I1..I8 are the description's sensors on those ports, encoded for the mode
 *   updateConfig gave the input: digital → 1 when the sensor's value is at least 0.5 (a touch
 *   sensor pressed); ultrasonic → centimetres (0..1023); voltage → millivolts and resistance →
 *   ohms, both as the sensor's {@code conversion} inverts its value. An input without a sensor
 *   reads 0 (resistance: 15000, open; ultrasonic: 1023, nothing in range).</li>
 *   <li><b>Link loss:</b> stopOnline stops every motor, and so does a silence of more than
 *   {@link #LINK_TIMEOUT_MILLIS} ms (a client that went away), as the controller ends its online
 *   mode when its client leaves.</li>
 * </ul>
 *
 * <h2>Ports</h2>
 * {@link #startOnTcpPair} serves the command port P and also accepts, and holds without
 * answering, connections on P + 2, the I²C port that ftrobopy's startOnline connects to, as a real
 * TXT does (P = 65000 makes it look like a real TXT to ftrobopy; 0 picks any free pair).
 * {@link #startOnTcp} serves the command port only, for tests of the command protocol alone.
 *
 * <p>Threads: as {@link BrickEmulator}; the firmware state is guarded by one lock.
 */
public final class TxtEmulator extends BrickEmulator {

    private static final Logger LOG = LoggerFactory.getLogger(TxtEmulator.class);

    /** The device name the emulator reports in its status. */
    public static final String DEVICE_NAME = "TXT-emulator";
    /** The firmware version it reports: 4.6.6. */
    public static final long FIRMWARE_VERSION = 0x04060600L;
    /** Motors stop after this long without any message from the client. */
    public static final long LINK_TIMEOUT_MILLIS = 1000;

    private static final int NO_SENSOR_RESISTANCE_OHMS = 15000;
    private static final int MAX_VOLTAGE_MV = 10000;
    private static final int ULTRASONIC_NOTHING_CM = 1023;

    private final Object firmware = new Object();
    private final String[] motorPort = new String[TxtProtocol.MOTORS];
    private final String[] countedMotor = new String[TxtProtocol.COUNTERS];
    private final SensorSpec[] sensorOn = new SensorSpec[TxtProtocol.INPUTS];
    private final int ticksPerRevolution;
    private final List<Socket> i2cPeers = new CopyOnWriteArrayList<>();
    private volatile ServerSocket i2cServer;
    private io.robomw.api.spi.OwnerThread i2cThread;
    // Guarded by firmware:
    private final int[] motorMode = {1, 1, 1, 1};
    private final int[] inputMode = new int[TxtProtocol.INPUTS];
    private final int[] inputDigital = new int[TxtProtocol.INPUTS];
    private final int[] pwm = new int[TxtProtocol.OUTPUTS];
    private final int[] dist = new int[TxtProtocol.MOTORS];
    private final int[] receivedMotorCmdId = new int[TxtProtocol.MOTORS];
    private final int[] finishedMotorCmdId = new int[TxtProtocol.MOTORS];
    private final boolean[] distanceRunning = new boolean[TxtProtocol.MOTORS];
    private final boolean[] distanceDone = new boolean[TxtProtocol.MOTORS];
    private final long[] distanceStart = new long[TxtProtocol.MOTORS];
    private final double[] pulses = new double[TxtProtocol.COUNTERS];
    private final double[] lastDegrees = new double[TxtProtocol.COUNTERS];
    private final long[] resetAt = new long[TxtProtocol.COUNTERS];
    private final int[] counterCmdId = new int[TxtProtocol.COUNTERS];
    private final double[] inputSi = new double[TxtProtocol.INPUTS];
    private boolean sampled;
    private boolean online;
    private long lastMessageNanos = System.nanoTime();

    /**
     * @param robot the simulated robot whose motors and sensors it drives
     * @throws IllegalArgumentException if the robot's motor ports are not M1..M4 or its wheel counters not C1..C4
     */
    public TxtEmulator(SimMotors robot) {
        super("ft-txt", robot, FRAMING);
        RobotDescription d = robot.robot().description();
        for (String port : d.motorPorts()) {
            motorPort[TxtPorts.motor(port)] = port;
        }
        for (Map.Entry<String, Integer> e : TxtPorts.wheelCounters(d.motors(), d.source()).entrySet()) {
            countedMotor[e.getValue()] = e.getKey();
        }
        this.ticksPerRevolution = d.drive().map(DifferentialDrive::encoderTicksPerRevolution).orElse(0);
        for (SensorSpec s : d.sensors()) {
            if (s.type() == SensorType.TACHO) {
                continue;
            }
            sensorOn[TxtPorts.input(s.port())] = s;
        }
        Arrays.fill(inputMode, TxtProtocol.MODE_RESISTANCE);
        Arrays.fill(inputDigital, 1);
        Arrays.fill(inputSi, Double.NaN);
    }

    /**
     * Binds an emulator to a robot of a simulation and steps it with the world.
     *
     * @param simulation the simulation (the robot must be one it emulates, see {@code Simulation.load(world, names)})
     * @param robotName  the robot
     * @return the emulator, not yet serving: call {@link #startOnTcp} or {@link #startOnTcpPair};
     *         closing it also unbinds it from the simulation
     */
    public static TxtEmulator bind(Simulation simulation, String robotName) {
        return bind(simulation, robotName, TxtEmulator::new);
    }

    /**
     * Frames by message id: reads the 4-byte id, then the rest of that request's fixed size; an id
     * outside the table is a {@link Framing.MalformedFrameException}. Replies go out as they are.
     */
    static final Framing FRAMING = new Framing() {
        @Override
        public byte[] read(Reader in) throws IOException {
            byte[] id = in.readExactly(TxtProtocol.ID_LENGTH);
            if (id == null) {
                return null;
            }
            long messageId = TxtProtocol.messageId(id);
            int length = TxtProtocol.requestLength(messageId);
            if (length < 0) {
                throw new MalformedFrameException(String.format("unknown TXT message id 0x%08X", messageId));
            }
            if (length == TxtProtocol.ID_LENGTH) {
                return id;
            }
            byte[] rest = in.readExactly(length - TxtProtocol.ID_LENGTH);
            if (rest == null) {
                return null;
            }
            byte[] message = Arrays.copyOf(id, length);
            System.arraycopy(rest, 0, message, TxtProtocol.ID_LENGTH, rest.length);
            return message;
        }

        @Override
        public byte[] encode(byte[] reply) {
            return reply;
        }
    };

    /**
     * Serves the command protocol on port P and accepts connections on P + 2 (I²C), as a real TXT
     * does when a client goes online: standard TXT clients (ftrobopy) connect to both.
     *
     * @param bindAddress the address to listen on (127.0.0.1 for tests)
     * @param port        the command port, 1..65533 (65000 like a real TXT), or 0 for any free P
     *                    whose P + 2 is free too
     * @return the command port
     * @throws IOException if either port cannot be bound
     * @throws IllegalArgumentException if the port is above 65533
     */
    public synchronized int startOnTcpPair(String bindAddress, int port) throws IOException {
        if (port == 0) {
            return startOnFreeTcpPair(bindAddress);
        }
        if (port < 0 || port > 65533) {
            throw new IllegalArgumentException("startOnTcpPair needs a port 1..65533, since it also listens on port + 2, or 0 for any free pair; got "
                    + port);
        }
        ServerSocket server = new ServerSocket();
        try {
            server.bind(new InetSocketAddress(bindAddress, port + 2));
            startOnTcp(bindAddress, port);
        } catch (IOException | RuntimeException e) {
            server.close();
            throw e;
        }
        i2cServer = server;
        i2cThread = io.robomw.sim.emulator.Acceptor.start("emulator-ft-txt-i2c-" + robot().robot().name(), server, this::heldI2c, failures());
        return port;
    }

    /** Tries free ports P from the operating system until P + 2 is free as well. */
    private int startOnFreeTcpPair(String bindAddress) throws IOException {
        IOException last = null;
        for (int attempt = 0; attempt < FREE_PAIR_ATTEMPTS; attempt++) {
            int candidate;
            try (ServerSocket probe = new ServerSocket()) {
                probe.bind(new InetSocketAddress(bindAddress, 0));
                candidate = probe.getLocalPort();
            }
            if (candidate > 65533) {
                continue;
            }
            try {
                return startOnTcpPair(bindAddress, candidate);
            } catch (IOException e) {
                last = e;
            }
        }
        throw new IOException("no free pair of TCP ports P and P + 2 on " + bindAddress + " in " + FREE_PAIR_ATTEMPTS + " attempts", last);
    }

    private static final int FREE_PAIR_ATTEMPTS = 20;

    /** An I²C client connected: held open until the emulator closes, not answered (the protocol there is unspecified). */
    private void heldI2c(Socket peer) {
        i2cPeers.add(peer);
        LOG.debug("ft-txt emulator for '{}': I²C client {} connected (held, not answered)", robot().robot().name(), peer.getRemoteSocketAddress());
    }

    /** @return the I²C port it also listens on, or -1 if it was not started with {@link #startOnTcpPair} */
    public int i2cPort() {
        ServerSocket s = i2cServer;
        return s == null ? -1 : s.getLocalPort();
    }

    /** A TXT over USB or WLAN: TCP with about a millisecond each way. */
    @Override
    protected LinkModel defaultLinkModel() {
        return new LinkModel(java.time.Duration.ofMillis(1), 0, 10);
    }

    // ---- simulation thread ----

    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            for (int c = 0; c < TxtProtocol.COUNTERS; c++) {
                if (countedMotor[c] == null) {
                    continue;
                }
                double degrees = robot.degrees(countedMotor[c]);
                if (sampled) {
                    pulses[c] += Math.abs(degrees - lastDegrees[c]) * ticksPerRevolution / 360.0;
                }
                lastDegrees[c] = degrees;
            }
            sampled = true;
            if (System.nanoTime() - lastMessageNanos > LINK_TIMEOUT_MILLIS * 1_000_000L && anyOutputOn()) {
                LOG.info("ft-txt emulator for '{}': no message for {} ms; motors off", robot.robot().name(), LINK_TIMEOUT_MILLIS);
                Arrays.fill(pwm, 0);
            }
            for (int i = 0; i < TxtProtocol.MOTORS; i++) {
                if (distanceRunning[i] && counted(i) >= dist[i]) {
                    distanceRunning[i] = false;
                    distanceDone[i] = true;
                    finishedMotorCmdId[i] = receivedMotorCmdId[i];
                }
                if (motorPort[i] != null) {
                    robot.command(motorPort[i], speed(i));
                }
            }
            for (int k = 0; k < TxtProtocol.INPUTS; k++) {
                inputSi[k] = sensorOn[k] == null ? Double.NaN : robot.siValue(sensorOn[k].name());
            }
        }
    }

    @Override
    protected void halt(SimMotors robot) {
        synchronized (firmware) {
            Arrays.fill(pwm, 0);
            for (String port : motorPort) {
                if (port != null) {
                    robot.command(port, 0);
                }
            }
        }
    }

    private boolean anyOutputOn() {
        for (int p : pwm) {
            if (p != 0) {
                return true;
            }
        }
        return false;
    }

    /** Pulses counter Ci has counted since motor Mi's distance command started. */
    private long counted(int motor) {
        return (long) Math.floor(pulses[motor]) - distanceStart[motor];
    }

    /** Motor Mi's speed now, degrees per second. */
    private double speed(int i) {
        if (motorMode[i] != 1 || distanceDone[i]) {
            return 0;
        }
        return (pwm[2 * i] - pwm[2 * i + 1]) / (double) TxtProtocol.PWM_MAX * FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER;
    }

    /**
     * Input k as the TXT reports it in its current mode, from the sensor's value sampled at the
     * last step (so a mode changed by updateConfig applies to the very next reply).
     */
    private int encodeInput(int k) {
        SensorSpec s = sensorOn[k];
        double si = inputSi[k];
        boolean absent = s == null || Double.isNaN(si);
        if (inputDigital[k] != 0) {
            return !absent && si >= 0.5 ? 1 : 0;
        }
        return switch (inputMode[k]) {
            case TxtProtocol.MODE_ULTRASONIC -> absent ? ULTRASONIC_NOTHING_CM : clamp(Math.round(si * 100), 0, ULTRASONIC_NOTHING_CM);
            case TxtProtocol.MODE_RESISTANCE -> absent ? NO_SENSOR_RESISTANCE_OHMS
                    : clamp(Math.round(s.conversion().invert(si)), 0, NO_SENSOR_RESISTANCE_OHMS);
            default -> absent ? 0 : clamp(Math.round(s.conversion().invert(si)), 0, MAX_VOLTAGE_MV);
        };
    }

    private static int clamp(long v, int lo, int hi) {
        return (int) Math.max(lo, Math.min(hi, v));
    }

    // ---- I/O thread ----

    @Override
    protected byte[] handle(byte[] frame) {
        long id = TxtProtocol.messageId(frame);
        synchronized (firmware) {
            lastMessageNanos = System.nanoTime();
            if (id == TxtProtocol.QUERY_STATUS) {
                return new TxtProtocol.Status(DEVICE_NAME, FIRMWARE_VERSION).encode();
            } else if (id == TxtProtocol.START_ONLINE) {
                online = true;
                return TxtProtocol.ack(TxtProtocol.START_ONLINE_REPLY);
            } else if (id == TxtProtocol.UPDATE_CONFIG) {
                configure(TxtProtocol.Config.decode(frame));
                return TxtProtocol.ack(TxtProtocol.UPDATE_CONFIG_REPLY);
            } else if (id == TxtProtocol.EXCHANGE) {
                apply(TxtProtocol.Exchange.decode(frame));
                return reply();
            } else if (id == TxtProtocol.STOP_ONLINE) {
                online = false;
                Arrays.fill(pwm, 0);
                return TxtProtocol.ack(TxtProtocol.STOP_ONLINE_REPLY);
            }
            throw new IllegalArgumentException(String.format("message id 0x%08X is not in the table", id));
        }
    }

    /** @return whether a client has started online mode and not stopped it */
    public boolean isOnline() {
        synchronized (firmware) {
            return online;
        }
    }

    private void configure(TxtProtocol.Config config) {
        if (config.extensionId() != 0) {
            return;
        }
        int[] motors = config.motor();
        for (int i = 0; i < TxtProtocol.MOTORS; i++) {
            motorMode[i] = motors[i];
        }
        System.arraycopy(config.inputMode(), 0, inputMode, 0, TxtProtocol.INPUTS);
        System.arraycopy(config.inputDigital(), 0, inputDigital, 0, TxtProtocol.INPUTS);
    }

    private void apply(TxtProtocol.Exchange x) {
        int[] newPwm = x.pwm();
        for (int i = 0; i < TxtProtocol.MOTORS; i++) {
            if (newPwm[2 * i] != pwm[2 * i] || newPwm[2 * i + 1] != pwm[2 * i + 1]) {
                distanceDone[i] = false;
            }
        }
        for (int o = 0; o < TxtProtocol.OUTPUTS; o++) {
            pwm[o] = clamp(newPwm[o], 0, TxtProtocol.PWM_MAX);
        }
        int[] ids = x.motorCmdId();
        int[] distances = x.motorDist();
        for (int i = 0; i < TxtProtocol.MOTORS; i++) {
            if (ids[i] == receivedMotorCmdId[i]) {
                continue;
            }
            receivedMotorCmdId[i] = ids[i];
            dist[i] = Math.max(0, distances[i]);
            distanceDone[i] = false;
            distanceStart[i] = (long) Math.floor(pulses[i]);
            distanceRunning[i] = dist[i] > 0;
            if (!distanceRunning[i]) {
                finishedMotorCmdId[i] = ids[i];
            }
        }
        int[] resets = x.counterCmdId();
        for (int c = 0; c < TxtProtocol.COUNTERS; c++) {
            if (resets[c] != counterCmdId[c]) {
                counterCmdId[c] = resets[c];
                resetAt[c] = (long) Math.floor(pulses[c]);
            }
        }
    }

    private byte[] reply() {
        int[] input = new int[TxtProtocol.INPUTS];
        for (int k = 0; k < TxtProtocol.INPUTS; k++) {
            input[k] = encodeInput(k);
        }
        int[] level = new int[TxtProtocol.COUNTERS];
        int[] value = new int[TxtProtocol.COUNTERS];
        for (int c = 0; c < TxtProtocol.COUNTERS; c++) {
            double p = pulses[c];
            level[c] = p - Math.floor(p) < 0.5 ? 1 : 0;
            value[c] = (int) ((long) Math.floor(p) - resetAt[c]);
        }
        return new TxtProtocol.ExchangeReply(input, level, value, counterCmdId, finishedMotorCmdId, 0,
                new byte[TxtProtocol.IR_LENGTH]).encode();
    }

    /**
     * Stops serving on both ports; at the next world step its motors stop and it unbinds from the
     * simulation.
     */
    @Override
    public synchronized void close() {
        ServerSocket s = i2cServer;
        if (s != null) {
            try {
                s.close();
            } catch (IOException e) {
                LOG.debug("ft-txt emulator: closing the I²C port: {}", e.toString());
            }
            for (Socket peer : i2cPeers) {
                try {
                    peer.close();
                } catch (IOException e) {
                    LOG.debug("ft-txt emulator: closing an I²C client: {}", e.toString());
                }
            }
            i2cPeers.clear();
            if (i2cThread != null) {
                i2cThread.close();
            }
        }
        super.close();
    }
}
