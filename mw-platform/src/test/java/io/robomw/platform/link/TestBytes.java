package io.robomw.platform.link;

import java.io.IOException;
import java.time.Duration;
import java.util.HexFormat;

import static org.junit.jupiter.api.Assertions.fail;

/** Byte helpers shared by the link tests. */
final class TestBytes {

    /** A timed read, as {@link Link#read} and {@link PseudoTerminal#read} offer it. */
    @FunctionalInterface
    interface TimedReader {
        int read(byte[] buf, int off, int len, Duration timeout) throws IOException;
    }

    private TestBytes() {
    }

    /** @return 0x00 to 0xFF in order */
    static byte[] allValues() {
        byte[] all = new byte[256];
        for (int i = 0; i < all.length; i++) {
            all[i] = (byte) i;
        }
        return all;
    }

    /** @return bytes parsed from {@code "0C 00 80"} */
    static byte[] hex(String spaced) {
        return HexFormat.ofDelimiter(" ").parseHex(spaced);
    }

    /** Reads exactly {@code n} bytes within {@code timeout}, or fails the test saying what came. */
    static byte[] readFully(TimedReader reader, int n, Duration timeout) throws IOException {
        Deadline deadline = Deadline.after(timeout);
        byte[] out = new byte[n];
        int got = 0;
        while (got < n) {
            if (deadline.expired()) {
                fail("received " + got + " of " + n + " bytes within " + timeout + ": "
                        + HexFormat.ofDelimiter(" ").formatHex(out, 0, got));
            }
            got += reader.read(out, got, n - got, Duration.ofNanos(deadline.remainingNanos()));
        }
        return out;
    }
}
