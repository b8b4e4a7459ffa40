package io.robomw.sim.emulator;

import java.time.Duration;
import java.util.Locale;
import java.util.Objects;

/**
 * How slow the link between a driver and a brick is, for emulators: every telegram (every write,
 * in either direction) takes {@code latency} to cross, plus the time its bytes take at the byte
 * rate ({@code bitsPerByte / baud} seconds each). Telegrams queue behind each other, as on a wire,
 * but their latencies overlap: a batch written back to back arrives back to back, one latency
 * later. A request and its reply therefore take {@code 2 × latency} plus both telegrams' bytes.
 *
 * @param latency     one-way delay of each telegram, not counting its bytes
 * @param baud        bits per second on the wire; 0 means no byte-rate limit
 * @param bitsPerByte bits each byte takes on the wire (10 for 8N1, 11 for 8O1)
 */
public record LinkModel(Duration latency, int baud, int bitsPerByte) {

    /** No delay: a pseudo-terminal or loopback socket as it is. */
    public static final LinkModel NONE = new LinkModel(Duration.ZERO, 0, 10);

    /**
     * A Bluetooth serial port (SPP), as NXT and EV3 bricks are usually reached: 15 ms each way per
     * telegram, so a direct command and its reply take about 30 ms (LEGO's Bluetooth Developer Kit
     * gives about 30 ms for the brick's Bluetooth module to turn from receiving to sending; ROBOTC
     * measured about 36 request/reply exchanges a second over NXT Bluetooth), at the 115200 baud
     * that SPP adapters usually present.
     */
    public static final LinkModel BLUETOOTH_SPP = new LinkModel(Duration.ofMillis(15), 115_200, 10);

    /** Checks the values. */
    public LinkModel {
        Objects.requireNonNull(latency, "latency");
        if (latency.isNegative()) {
            throw new IllegalArgumentException("link latency must be >= 0, got " + latency);
        }
        if (baud < 0) {
            throw new IllegalArgumentException("link baud must be >= 0 (0 = no byte-rate limit), got " + baud);
        }
        if (bitsPerByte < 1) {
            throw new IllegalArgumentException("bits per byte must be >= 1, got " + bitsPerByte);
        }
    }

    /**
     * @param baud        the serial line's baud rate
     * @param bitsPerByte bits per byte with start, parity and stop bits (10 for 8N1, 11 for 8O1)
     * @return a serial line without latency beyond its bytes' time
     */
    public static LinkModel serial(int baud, int bitsPerByte) {
        return new LinkModel(Duration.ZERO, baud, bitsPerByte);
    }

    /**
     * @param latency the one-way latency
     * @return this model with another latency
     */
    public LinkModel withLatency(Duration latency) {
        return new LinkModel(latency, baud, bitsPerByte);
    }

    /**
     * @param baud the baud rate, 0 for no byte-rate limit
     * @return this model with another baud rate
     */
    public LinkModel withBaud(int baud) {
        return new LinkModel(latency, baud, bitsPerByte);
    }

    /** @return whether this model delays nothing */
    public boolean isNone() {
        return latency.isZero() && baud == 0;
    }

    /**
     * @param bytes a telegram's length
     * @return how long its bytes take on the wire, nanoseconds
     */
    public long transmissionNanos(int bytes) {
        return baud == 0 ? 0 : (long) bytes * bitsPerByte * 1_000_000_000L / baud;
    }

    @Override
    public String toString() {
        if (isNone()) {
            return "no link delay";
        }
        return String.format(Locale.ROOT, "%d ms per telegram each way%s", latency.toMillis(),
                baud == 0 ? "" : String.format(Locale.ROOT, ", %d baud (%d bits a byte)", baud, bitsPerByte));
    }
}
