package io.robomw.platform.nxt.bench;

import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.link.Communicator;
import io.robomw.platform.link.PseudoTerminal;
import io.robomw.platform.link.SerialLink;
import io.robomw.platform.link.SerialSettings;
import io.robomw.platform.nxt.NxtBrick;
import io.robomw.platform.nxt.NxtTelegram;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.time.Duration;
import java.util.Arrays;
import java.util.HexFormat;
import java.util.Locale;

/**
 * The NXT command round trip over a pseudo-terminal through jSerialComm: GETINPUTVALUES sent by
 * the driver ({@link NxtBrick} over {@link BrickChannel}, {@link Communicator}, {@link SerialLink})
 * against a bare write and read of the same bytes on the same kind of device pair, answered by the
 * same responder (a canned reply, so only the driver differs). Batches of the two alternate, so
 * drift affects both alike. Prints p50/p99 of each and the driver's overhead.
 *
 * <p>Run on demand: {@code bench/nxt-roundtrip} (see {@code docs/benchmarks.md}). Not a test.
 */
public final class NxtRoundTripBenchmark {

    private static final byte[] REPLY = HexFormat.of().parseHex("1000" + "0207000001000120b700b7000100b700");
    private static final byte[] REQUEST = NxtTelegram.withLengthPrefix(NxtTelegram.getInputValues(0));

    private NxtRoundTripBenchmark() {
    }

    /**
     * @param args rounds per batch (default 2000) and batches (default 10)
     * @throws Exception if a pseudo-terminal cannot be used
     */
    public static void main(String[] args) throws Exception {
        int perBatch = args.length > 0 ? Integer.parseInt(args[0]) : 2000;
        int batches = args.length > 1 ? Integer.parseInt(args[1]) : 10;
        try (PseudoTerminal barePty = PseudoTerminal.open(); PseudoTerminal driverPty = PseudoTerminal.open()) {
            Thread a = responder(barePty);
            Thread b = responder(driverPty);
            SerialSettings settings = SerialSettings.of(115200, 8, SerialSettings.Parity.NONE, 1);
            SerialLink bare = new SerialLink(barePty.devicePath(), settings);
            bare.open();
            Communicator communicator = new Communicator(new SerialLink(driverPty.devicePath(), settings));
            communicator.open();
            NxtBrick brick = new NxtBrick("bench", new BrickChannel("bench", communicator, Duration.ofSeconds(1)));
            long[] bareTimes = new long[perBatch * batches];
            long[] driverTimes = new long[perBatch * batches];
            run(bare, brick, 1000, new long[1000], new long[1000]);
            for (int i = 0; i < batches; i++) {
                long[] bt = new long[perBatch];
                long[] dt = new long[perBatch];
                run(bare, brick, perBatch, bt, dt);
                System.arraycopy(bt, 0, bareTimes, i * perBatch, perBatch);
                System.arraycopy(dt, 0, driverTimes, i * perBatch, perBatch);
            }
            bare.close();
            communicator.close();
            Arrays.sort(bareTimes);
            Arrays.sort(driverTimes);
            double bareP50 = bareTimes[bareTimes.length / 2] / 1000.0;
            double driverP50 = driverTimes[driverTimes.length / 2] / 1000.0;
            System.out.printf(Locale.ROOT, "machine: %d processors, %s %s; %d round trips each%n", Runtime.getRuntime().availableProcessors(),
                    System.getProperty("java.vm.name"), System.getProperty("java.version"), bareTimes.length);
            System.out.println("| round trip (GETINPUTVALUES, 5 + 18 bytes) | p50 µs | p99 µs |");
            System.out.println("|---|---|---|");
            System.out.printf(Locale.ROOT, "| bare write/read on the pty | %.1f | %.1f |%n", bareP50, bareTimes[bareTimes.length * 99 / 100] / 1000.0);
            System.out.printf(Locale.ROOT, "| NXT driver (NxtBrick.request) | %.1f | %.1f |%n", driverP50, driverTimes[driverTimes.length * 99 / 100] / 1000.0);
            System.out.printf(Locale.ROOT, "driver overhead at p50: %.1f µs (target ≤ 50 µs)%n", driverP50 - bareP50);
            // for bench/all (io.robomw.bench.BenchReport in src-it reads these)
            System.out.printf(Locale.ROOT, "BENCH nxt.bare %.6g µs%nBENCH nxt.driver %.6g µs%n", bareP50, driverP50);
            a.interrupt();
            b.interrupt();
        }
    }

    private static void run(SerialLink bare, NxtBrick brick, int n, long[] bareTimes, long[] driverTimes) throws IOException {
        byte[] in = new byte[REPLY.length];
        for (int i = 0; i < n; i++) {
            long t0 = System.nanoTime();
            bare.write(REQUEST, 0, REQUEST.length);
            int got = 0;
            while (got < in.length) {
                got += bare.read(in, got, in.length - got, Duration.ofSeconds(1));
            }
            long t1 = System.nanoTime();
            brick.request(NxtTelegram.getInputValues(0), NxtTelegram.GETINPUTVALUES_REPLY, 0);
            long t2 = System.nanoTime();
            bareTimes[i] = t1 - t0;
            driverTimes[i] = t2 - t1;
        }
    }

    /** Answers every length-prefixed telegram with the canned GETINPUTVALUES reply. */
    private static Thread responder(PseudoTerminal pty) {
        Thread t = new Thread(() -> {
            InputStream in = pty.masterInput();
            OutputStream out = pty.masterOutput();
            byte[] header = new byte[2];
            try {
                while (!Thread.currentThread().isInterrupted()) {
                    if (in.readNBytes(header, 0, 2) < 2) {
                        return;
                    }
                    int length = (header[0] & 0xFF) | (header[1] & 0xFF) << 8;
                    if (in.readNBytes(new byte[length], 0, length) < length) {
                        return;
                    }
                    out.write(REPLY);
                    out.flush();
                }
            } catch (IOException e) {
                // the pseudo-terminal closed: the benchmark is over
            }
        }, "bench-responder");
        t.setDaemon(true);
        t.start();
        return t;
    }
}
