package io.robomw.sim.bench;

import io.robomw.api.Robot;
import io.robomw.api.Robots;
import io.robomw.platform.mavlink.wire.Frame;
import io.robomw.platform.mavlink.wire.FrameDecoder;
import io.robomw.platform.mavlink.wire.FrameEncoder;
import io.robomw.platform.mavlink.wire.MavAutopilot;
import io.robomw.platform.mavlink.wire.MavType;
import io.robomw.platform.mavlink.wire.Messages;
import io.robomw.platform.mavlink.wire.ModeFlag;
import io.robomw.platform.mavlink.wire.Payload;

import java.net.DatagramPacket;
import java.net.DatagramSocket;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.SocketAddress;
import java.net.SocketTimeoutException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.locks.LockSupport;

/**
 * From {@code robot.drive(v, ω)} to the setpoint on the wire: a rover robot (vehicle drive,
 * {@code platform: mavlink}, cycle 100 Hz) opened through all three layers against a minimal
 * vehicle on loopback (this process: a UDP socket that sends HEARTBEAT, LOCAL_POSITION_NED and
 * ATTITUDE and stamps every SET_POSITION_TARGET_LOCAL_NED it receives with {@link System#nanoTime}).
 * <ul>
 *   <li><b>latency</b>: each sample calls {@code drive(v, 0)} with a new {@code v} and waits for the
 *   first setpoint carrying it; the baseline, in the same round, interleaved sample by sample, is a
 *   plain {@link DatagramSocket#send} of a frame of the same size from the calling thread to the
 *   same receiver;</li>
 *   <li><b>jitter</b>: a continuous {@code drive} kept up for 5 s; the intervals between setpoints
 *   (the driver streams at 20 Hz: 50 ms), their spread.</li>
 * </ul>
 * Rounds (default 5) repeat both; the report gives each figure's median over the rounds, and the
 * smallest and largest round. Run on demand: {@code bench/vehicle-setpoint}. Not a test.
 */
public final class VehicleSetpointBenchmark {

    private VehicleSetpointBenchmark() {
    }

    /** The vehicle: sends its telemetry to the driver, stamps the setpoints it receives. */
    private static final class Vehicle implements AutoCloseable {
        final DatagramSocket socket = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0));
        final FrameEncoder encoder = new FrameEncoder(1, 1);
        final List<long[]> setpoints = new CopyOnWriteArrayList<>();   // {nanos, vx bits}
        final ConcurrentHashMap<Long, Long> baseline = new ConcurrentHashMap<>();
        volatile SocketAddress gcs;
        volatile boolean open = true;
        final Thread reader;
        final Thread talker;

        Vehicle() throws Exception {
            reader = new Thread(this::read, "bench-vehicle-rx");
            talker = new Thread(this::talk, "bench-vehicle-tx");
            reader.setDaemon(true);
            talker.setDaemon(true);
            reader.start();
            talker.start();
        }

        int port() {
            return socket.getLocalPort();
        }

        private void read() {
            byte[] buf = new byte[2048];
            List<Frame> frames = new ArrayList<>();
            FrameDecoder d = new FrameDecoder(frames::add);
            try {
                socket.setSoTimeout(100);
                while (open) {
                    DatagramPacket p = new DatagramPacket(buf, buf.length);
                    try {
                        socket.receive(p);
                    } catch (SocketTimeoutException e) {
                        continue;
                    }
                    long at = System.nanoTime();
                    if (p.getLength() == 8) {
                        long id = java.nio.ByteBuffer.wrap(buf, 0, 8).getLong();
                        baseline.put(id, at);
                        continue;
                    }
                    gcs = p.getSocketAddress();
                    frames.clear();
                    d.feedDatagram(p.getData(), 0, p.getLength());
                    for (Frame f : frames) {
                        if (f.is(Messages.SetPositionTargetLocalNed.MESSAGE)) {
                            setpoints.add(new long[]{at, Double.doubleToLongBits(f.payload().getDouble(Messages.SetPositionTargetLocalNed.VX))});
                        }
                    }
                }
            } catch (Exception e) {
                if (open) {
                    e.printStackTrace();
                }
            }
        }

        private void talk() {
            long next = System.nanoTime();
            int n = 0;
            while (open) {
                SocketAddress to = gcs;
                try {
                    if (to != null) {
                        send(to, Payload.of(Messages.LocalPositionNed.MESSAGE));
                        send(to, Payload.of(Messages.Attitude.MESSAGE));
                        if (n % 10 == 0) {
                            send(to, Payload.of(Messages.Heartbeat.MESSAGE).set(Messages.Heartbeat.TYPE, MavType.GROUND_ROVER.code())
                                    .set(Messages.Heartbeat.AUTOPILOT, MavAutopilot.ARDUPILOTMEGA.code())
                                    .set(Messages.Heartbeat.BASE_MODE, ModeFlag.CUSTOM_MODE_ENABLED.code() | ModeFlag.SAFETY_ARMED.code())
                                    .set(Messages.Heartbeat.CUSTOM_MODE, 15));
                        }
                    }
                } catch (Exception e) {
                    if (open) {
                        e.printStackTrace();
                    }
                }
                n++;
                next += 100_000_000L;
                LockSupport.parkNanos(Math.max(0, next - System.nanoTime()));
            }
        }

        private void send(SocketAddress to, Payload p) throws Exception {
            byte[] f = encoder.encode(p);
            socket.send(new DatagramPacket(f, f.length, to));
        }

        @Override
        public void close() {
            open = false;
            socket.close();
        }
    }

    /**
     * @param args rounds (default 5), samples per round (default 200)
     * @throws Exception if loopback cannot be used
     */
    public static void main(String[] args) throws Exception {
        int rounds = args.length > 0 ? Integer.parseInt(args[0]) : 5;
        int samples = args.length > 1 ? Integer.parseInt(args[1]) : 200;
        Path dir = Files.createTempDirectory("vehicle-bench");
        try (Vehicle vehicle = new Vehicle(); DatagramSocket plain = new DatagramSocket(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0))) {
            // the vehicle starts talking once it knows where the ground station is: prime it with a datagram from a port of the driver's? The
            // driver sends first (udpout), so the vehicle learns the driver's address from its HEARTBEAT.
            Path robotFile = Files.writeString(dir.resolve("rover.yaml"), """
                    name: bench-rover
                    platform: mavlink
                    connection: { link: "udpout://127.0.0.1:%d", connect_timeout_ms: 10000 }
                    cycle_hz: 100
                    watchdog: 0.5
                    drive: { type: vehicle, medium: ground, max_speed: 10, max_turn_rate: 2, acceptance_radius: 0.3 }
                    """.formatted(vehicle.port()));
            double[] latency = new double[rounds];
            double[] base = new double[rounds];
            double[] jitterP50 = new double[rounds];
            double[] jitterP99 = new double[rounds];
            double[] interval = new double[rounds];
            try (Robot robot = Robots.open(robotFile)) {
                InetSocketAddress to = new InetSocketAddress(InetAddress.getLoopbackAddress(), vehicle.port());
                for (int r = 0; r < rounds; r++) {
                    long[] rl = new long[samples];
                    long[] bl = new long[samples];
                    for (int i = 0; i < samples; i++) {
                        long id = (long) r * samples + i + 1;
                        byte[] b = java.nio.ByteBuffer.allocate(8).putLong(id).array();
                        long t0 = System.nanoTime();
                        plain.send(new DatagramPacket(b, b.length, to));
                        while (!vehicle.baseline.containsKey(id)) {
                            Thread.onSpinWait();
                        }
                        bl[i] = vehicle.baseline.get(id) - t0;
                        double v = 0.001 * ((r * samples + i) % 5000 + 1);
                        int seen = vehicle.setpoints.size();
                        t0 = System.nanoTime();
                        robot.drive(v, 0);
                        long arrived = -1;
                        while (arrived < 0) {
                            for (int k = seen; k < vehicle.setpoints.size(); k++) {
                                long[] s = vehicle.setpoints.get(k);
                                if ((float) Double.longBitsToDouble(s[1]) == (float) v) {
                                    arrived = s[0];
                                    break;
                                }
                            }
                            Thread.onSpinWait();
                        }
                        rl[i] = arrived - t0;
                        LockSupport.parkNanos(20_000_000L);
                    }
                    Arrays.sort(rl);
                    Arrays.sort(bl);
                    latency[r] = rl[samples / 2] / 1e3;
                    base[r] = bl[samples / 2] / 1e3;
                    // jitter: a continuous drive, refreshed every 100 ms (under the 0.5 s watchdog), for 5 s
                    int from = vehicle.setpoints.size();
                    long end = System.nanoTime() + 5_000_000_000L;
                    while (System.nanoTime() < end) {
                        robot.drive(0.5, 0);
                        LockSupport.parkNanos(100_000_000L);
                    }
                    List<long[]> stream = List.copyOf(vehicle.setpoints);
                    stream = stream.subList(Math.min(from, stream.size()), stream.size());
                    long[] gaps = new long[stream.size() - 1];
                    for (int k = 1; k < stream.size(); k++) {
                        gaps[k - 1] = stream.get(k)[0] - stream.get(k - 1)[0];
                    }
                    // refreshes send at once too: take the stream's own ticks (gaps of 25 ms or more)
                    long[] ticks = Arrays.stream(gaps).filter(g -> g >= 25_000_000L).sorted().toArray();
                    long[] dev = Arrays.stream(ticks).map(g -> Math.abs(g - 50_000_000L)).sorted().toArray();
                    interval[r] = ticks[ticks.length / 2] / 1e6;
                    jitterP50[r] = dev[dev.length / 2] / 1e6;
                    jitterP99[r] = dev[(int) (dev.length * 0.99)] / 1e6;
                    int streamed = stream.size();
                    robot.stop();
                    System.out.printf(Locale.ROOT, "round %d: drive→wire p50 %.0f µs, plain UDP p50 %.0f µs; stream interval p50 %.2f ms, |jitter| p50 %.2f ms,"
                            + " p99 %.2f ms (%d setpoints)%n", r + 1, latency[r], base[r], interval[r], jitterP50[r], jitterP99[r], streamed);
                }
            }
            System.out.printf(Locale.ROOT, "machine: %d processors, %s %s; %d rounds of %d samples; load average %s%n",
                    Runtime.getRuntime().availableProcessors(), System.getProperty("java.vm.name"), System.getProperty("java.version"), rounds, samples,
                    Files.readString(Path.of("/proc/loadavg")).strip());
            System.out.println("| figure | median of rounds | min | max |");
            System.out.println("|---|---:|---:|---:|");
            row("drive(v, ω) → setpoint on the wire, p50 (µs)", latency, "%.0f");
            row("plain UDP send → receipt, p50 (µs)", base, "%.0f");
            row("setpoint stream interval, p50 (ms; 50 wanted)", interval, "%.2f");
            row("stream |jitter|, p50 (ms)", jitterP50, "%.2f");
            row("stream |jitter|, p99 (ms)", jitterP99, "%.2f");
        }
    }

    private static void row(String what, double[] values, String format) {
        double[] v = values.clone();
        Arrays.sort(v);
        System.out.printf(Locale.ROOT, "| %s | " + format + " | " + format + " | " + format + " |%n", what, v[v.length / 2], v[0], v[v.length - 1]);
    }
}
