package io.robomw.platform.mavlink.wire;

import java.time.InstantSource;
import java.util.Objects;

/**
 * Signs the frames one sender sends on one link: its key, its link id and its timestamps, which
 * must increase from one frame to the next (a receiver refuses a timestamp it has seen, per
 * sender and link): each frame gets {@code max(now, last + 1)}. Thread-safe.
 */
public final class Signer {

    private final SigningKey key;
    private final int linkId;
    private final InstantSource clock;
    private long last;

    /**
     * @param key    the secret key
     * @param linkId this link's id, 0-255
     * @param clock  the wall clock the timestamps come from
     */
    public Signer(SigningKey key, int linkId, InstantSource clock) {
        this.key = Objects.requireNonNull(key, "key");
        if (linkId < 0 || linkId > 255) {
            throw new IllegalArgumentException("a signing link id is 0-255, got " + linkId);
        }
        this.linkId = linkId;
        this.clock = Objects.requireNonNull(clock, "clock");
    }

    /**
     * Starts the timestamps at a given value (for known-answer tests, and SETUP_SIGNING's initial
     * timestamp): the next frame gets at least {@code timestamp}.
     *
     * @param timestamp a signing timestamp
     * @return this
     */
    public synchronized Signer startingAt(long timestamp) {
        last = Math.max(last, timestamp - 1);
        return this;
    }

    /** @return the key */
    public SigningKey key() {
        return key;
    }

    /** @return the link id */
    public int linkId() {
        return linkId;
    }

    synchronized long nextTimestamp() {
        long now = SigningTime.of(clock.instant());
        last = Math.min(SigningTime.MAX, Math.max(now, last + 1));
        return last;
    }

    /**
     * Writes the signature block after a frame's checksum.
     *
     * @param frame    the frame's buffer, with room for the 13 bytes
     * @param unsigned the length of the frame up to its checksum (included)
     */
    void sign(byte[] frame, int unsigned) {
        long ts = nextTimestamp();
        frame[unsigned] = (byte) linkId;
        for (int i = 0; i < Framing.TIMESTAMP; i++) {
            frame[unsigned + 1 + i] = (byte) (ts >>> (8 * i));
        }
        byte[] sig = key.signature(frame, 0, unsigned + 1 + Framing.TIMESTAMP);
        System.arraycopy(sig, 0, frame, unsigned + 1 + Framing.TIMESTAMP, Framing.SIGNATURE);
    }
}
