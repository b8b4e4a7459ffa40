package io.robomw.bench;

import com.amazon.corretto.crypto.provider.AmazonCorrettoCryptoProvider;

import javax.crypto.Cipher;
import javax.crypto.Mac;
import javax.crypto.spec.GCMParameterSpec;
import javax.crypto.spec.SecretKeySpec;
import java.io.DataInputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.ByteBuffer;
import java.nio.channels.FileChannel;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.security.GeneralSecurityException;
import java.util.Arrays;
import java.util.Locale;
import java.util.concurrent.ThreadLocalRandom;
import java.util.function.LongSupplier;

/**
 * The machine's own ceilings, measured in the same run as the figures they bound ({@code bench/all}):
 * what plain Java on this machine does with nothing of RoboMW in the way.
 *
 * <ul>
 *   <li>loopback TCP: 64-byte ping-pong between two threads of one JVM (p50), and bulk throughput
 *   (64 KiB writes, one direction) of plain {@link Socket}s;</li>
 *   <li>memory: copying 1 MiB into an existing array ({@code System.arraycopy}) and into a fresh one
 *   ({@code Arrays.copyOf}: a new large array is zeroed and, for G1, humongous), as a hop's copies are;</li>
 *   <li>authenticators: HMAC-SHA256, AES-256-GCM used as a MAC (GMAC: the frame as additional
 *   authenticated data) and the agent hosts' GCM tag (the frame through GCM in 16 KiB chunks, the
 *   tag kept) on 1 MiB and on 600 bytes (a small agent's transfer call), and AES-256-GCM
 *   encryption of 1 MiB, through the JDK's providers (SHA, AES and carry-less multiply intrinsics);</li>
 *   <li>{@code fdatasync}: a 512-byte record overwritten in a preallocated file in the temporary
 *   directory (where the agent benchmark keeps its journals), then {@code FileChannel.force(false)}.</li>
 * </ul>
 *
 * <p>Prints one {@code BENCH} line per figure (see {@link BenchReport}). Run by {@code bench/all};
 * {@code --smoke} measures for a tenth of the time.
 */
public final class Ceilings {

    private final double scale;

    private Ceilings(double scale) {
        this.scale = scale;
    }

    /**
     * @param args {@code --smoke} for short windows
     * @throws Exception on failure
     */
    public static void main(String[] args) throws Exception {
        Ceilings c = new Ceilings(Arrays.asList(args).contains("--smoke") ? 0.1 : 1);
        c.tcpPingPong();
        c.tcpBulk();
        c.copies();
        c.authenticators();
        c.fdatasync();
    }

    private static void bench(String id, double value, String unit) {
        System.out.println(BenchReport.line(id, value, unit));
    }

    private long millis(long full) {
        return Math.max(50, Math.round(full * scale));
    }

    // ---- loopback TCP ----

    private void tcpPingPong() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
             Socket client = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort());
             Socket echo = server.accept()) {
            client.setTcpNoDelay(true);
            echo.setTcpNoDelay(true);
            Thread t = new Thread(() -> {
                try {
                    DataInputStream in = new DataInputStream(echo.getInputStream());
                    OutputStream out = echo.getOutputStream();
                    byte[] b = new byte[64];
                    while (true) {
                        in.readFully(b);
                        out.write(b);
                    }
                } catch (IOException done) {
                    // the client closed
                }
            }, "ceiling-echo");
            t.setDaemon(true);
            t.start();
            DataInputStream in = new DataInputStream(client.getInputStream());
            OutputStream out = client.getOutputStream();
            byte[] b = new byte[64];
            LongSupplier rt = () -> {
                try {
                    long t0 = System.nanoTime();
                    out.write(b);
                    in.readFully(b);
                    return System.nanoTime() - t0;
                } catch (IOException e) {
                    throw new java.io.UncheckedIOException(e);
                }
            };
            int n = (int) Math.max(2000, 100_000 * scale);
            for (int i = 0; i < n / 5; i++) {
                rt.getAsLong();
            }
            long[] times = new long[n];
            for (int i = 0; i < n; i++) {
                times[i] = rt.getAsLong();
            }
            Arrays.sort(times);
            bench("ceiling.tcp-pingpong-64B", times[n / 2] / 1000.0, "µs");
        }
    }

    private void tcpBulk() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
             Socket client = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort());
             Socket sink = server.accept()) {
            long[] received = new long[1];
            Thread t = new Thread(() -> {
                try {
                    InputStream in = sink.getInputStream();
                    byte[] b = new byte[1 << 16];
                    for (int r; (r = in.read(b)) > 0; ) {
                        synchronized (received) {
                            received[0] += r;
                        }
                    }
                } catch (IOException done) {
                    // closed
                }
            }, "ceiling-sink");
            t.setDaemon(true);
            t.start();
            OutputStream out = client.getOutputStream();
            byte[] b = new byte[1 << 16];
            long warm = System.nanoTime() + millis(1000) * 1_000_000;
            while (System.nanoTime() < warm) {
                out.write(b);
            }
            long r0;
            synchronized (received) {
                r0 = received[0];
            }
            long t0 = System.nanoTime();
            long end = t0 + millis(3000) * 1_000_000;
            while (System.nanoTime() < end) {
                out.write(b);
            }
            long r1;
            synchronized (received) {
                r1 = received[0];
            }
            long t1 = System.nanoTime();
            bench("ceiling.tcp-bulk", (r1 - r0) / 1e6 / ((t1 - t0) / 1e9), "MB/s");
        }
    }

    // ---- memory ----

    private void copies() {
        byte[] src = new byte[1 << 20];
        ThreadLocalRandom.current().nextBytes(src);
        byte[] dst = new byte[src.length];
        bench("ceiling.copy-1MiB", rate(src.length, () -> System.arraycopy(src, 0, dst, 0, src.length)) / 1e3, "GB/s");
        byte[][] keep = new byte[1][];
        bench("ceiling.copy-fresh-1MiB", rate(src.length, () -> keep[0] = Arrays.copyOf(src, src.length)) / 1e3, "GB/s");
    }

    /** @return MB/s of a task that handles {@code bytes} per call, over a timed window after a warm-up */
    private double rate(long bytes, Runnable task) {
        long warm = System.nanoTime() + millis(1000) * 1_000_000;
        while (System.nanoTime() < warm) {
            task.run();
        }
        long t0 = System.nanoTime();
        long end = t0 + millis(2000) * 1_000_000;
        long calls = 0;
        long now;
        do {
            task.run();
            calls++;
        } while ((now = System.nanoTime()) < end);
        return calls * bytes / 1e6 / ((now - t0) / 1e9);
    }

    /** @return nanoseconds per call of a task, over a timed window after a warm-up */
    private double nanosPerCall(Runnable task) {
        return 1e6 / rate(1000, task); // rate's MB/s at 1000 bytes a call is thousands of calls a second
    }

    // ---- authenticators ----

    private void authenticators() throws GeneralSecurityException {
        byte[] key = new byte[32];
        ThreadLocalRandom.current().nextBytes(key);
        Mac hmac = Mac.getInstance("HmacSHA256");
        hmac.init(new SecretKeySpec(key, "HmacSHA256"));
        SecretKeySpec aes = new SecretKeySpec(key, "AES");
        Cipher gcm = Cipher.getInstance("AES/GCM/NoPadding");
        byte[] big = new byte[1 << 20];
        byte[] small = new byte[600];
        byte[] out = new byte[big.length + 16];
        long[] counter = {0};
        Runnable hmacBig = () -> {
            hmac.update(big);
            hmac.doFinal();
        };
        Runnable hmacSmall = () -> {
            hmac.update(small);
            hmac.doFinal();
        };
        Runnable gmacBig = () -> gmac(gcm, aes, ++counter[0], big, out);
        Runnable gmacSmall = () -> gmac(gcm, aes, ++counter[0], small, out);
        Runnable encryptBig = () -> {
            try {
                gcm.init(Cipher.ENCRYPT_MODE, aes, new GCMParameterSpec(128, nonce(++counter[0])));
                gcm.doFinal(big, 0, big.length, out, 0);
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException(e);
            }
        };
        byte[] scratch = new byte[(16 << 10) + 16];
        Runnable tagBig = () -> gcmTag(gcm, aes, ++counter[0], big, scratch);
        Runnable tagSmall = () -> gcmTag(gcm, aes, ++counter[0], small, scratch);
        bench("ceiling.hmac-sha256-1MiB", rate(big.length, hmacBig), "MB/s");
        bench("ceiling.gmac-aes256-1MiB", rate(big.length, gmacBig), "MB/s");
        bench("ceiling.gcm-tag-aes256-1MiB", rate(big.length, tagBig), "MB/s");
        bench("ceiling.aes256-gcm-encrypt-1MiB", rate(big.length, encryptBig), "MB/s");
        bench("ceiling.hmac-sha256-600B", nanosPerCall(hmacSmall) / 1000, "µs");
        bench("ceiling.gmac-aes256-600B", nanosPerCall(gmacSmall) / 1000, "µs");
        bench("ceiling.gcm-tag-aes256-600B", nanosPerCall(tagSmall) / 1000, "µs");
        // The hosts' provider where it loads (mw-agents AesGcm), in the wire's 64 KiB pieces.
        Throwable accpError = AmazonCorrettoCryptoProvider.INSTANCE.getLoadingError();
        if (accpError != null) {
            System.out.println("ceiling: the Amazon Corretto Crypto Provider did not load here (" + accpError + "): no ACCP ceilings");
            return;
        }
        Cipher accp = Cipher.getInstance("AES/GCM/NoPadding", AmazonCorrettoCryptoProvider.INSTANCE);
        byte[] wideScratch = new byte[(64 << 10) + 16];
        bench("ceiling.gcm-tag-accp-1MiB", rate(big.length, () -> gcmTag(accp, aes, ++counter[0], big, wideScratch)), "MB/s");
        bench("ceiling.gcm-tag-accp-600B", nanosPerCall(() -> gcmTag(accp, aes, ++counter[0], small, wideScratch)) / 1000, "µs");
    }

    private static void gmac(Cipher gcm, SecretKeySpec key, long n, byte[] data, byte[] out) {
        try {
            gcm.init(Cipher.ENCRYPT_MODE, key, new GCMParameterSpec(128, nonce(n)));
            gcm.updateAAD(data);
            gcm.doFinal(out, 0);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException(e);
        }
    }

    /** The agent hosts' tag (CallAuthenticator code 2): the data through AES-GCM in 16 KiB chunks into a scratch buffer, the tag kept. */
    private static void gcmTag(Cipher gcm, SecretKeySpec key, long n, byte[] data, byte[] scratch) {
        try {
            gcm.init(Cipher.ENCRYPT_MODE, key, new GCMParameterSpec(128, nonce(n)));
            int chunk = scratch.length - 16;
            int at = 0;
            while (data.length - at > chunk) {
                gcm.update(data, at, chunk, scratch, 0);
                at += chunk;
            }
            gcm.doFinal(data, at, data.length - at, scratch, 0);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException(e);
        }
    }

    private static byte[] nonce(long n) {
        return ByteBuffer.allocate(12).putLong(4, n).array();
    }

    // ---- fdatasync ----

    private void fdatasync() throws IOException {
        Path dir = Files.createTempDirectory("robomw-ceiling");
        Path file = dir.resolve("sync");
        try (FileChannel c = FileChannel.open(file, StandardOpenOption.CREATE, StandardOpenOption.WRITE)) {
            ByteBuffer zeros = ByteBuffer.allocate(4 << 20);
            while (zeros.hasRemaining()) {
                c.write(zeros);
            }
            c.force(true);
            ByteBuffer record = ByteBuffer.allocate(512);
            int n = (int) Math.max(100, 2000 * scale);
            long[] times = new long[n];
            for (int i = 0; i < n; i++) {
                record.clear();
                long at = (long) (i % 8192) * 512;
                long t0 = System.nanoTime();
                while (record.hasRemaining()) {
                    at += c.write(record, at);
                }
                c.force(false);
                times[i] = System.nanoTime() - t0;
            }
            Arrays.sort(times);
            bench("ceiling.fdatasync-512B", times[n / 2] / 1000.0, "µs");
        } finally {
            Files.deleteIfExists(file);
            Files.deleteIfExists(dir);
        }
    }
}
