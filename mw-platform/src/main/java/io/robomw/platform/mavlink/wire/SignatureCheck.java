package io.robomw.platform.mavlink.wire;

import java.security.MessageDigest;
import java.time.InstantSource;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;

/**
 * Checks the signatures of incoming frames as mavlink.io's message signing page says a receiver
 * must:
 * <ol>
 *   <li>a frame without a signature is {@link Verdict#UNSIGNED} (the caller decides: a vehicle
 *   with a key ignores it);</li>
 *   <li>a wrong signature is {@link Verdict#WRONG_SIGNATURE};</li>
 *   <li>each logical stream (sender's system id, component id and link id) must bring increasing
 *   timestamps: one not above the stream's last is {@link Verdict#REPLAYED};</li>
 *   <li>a stream not seen before whose timestamp is more than a minute behind this receiver's
 *   time (the largest of its clock and every timestamp accepted) is {@link Verdict#TOO_OLD}.</li>
 * </ol>
 * It remembers at most {@value #MAX_STREAMS} streams, the least recently heard forgotten first (a
 * forgotten stream is a new stream again, still held to the one-minute rule).
 *
 * <p>Thread-safe.
 */
public final class SignatureCheck {

    /** The most streams remembered. */
    public static final int MAX_STREAMS = 256;

    /** What a frame's signature says. */
    public enum Verdict {
        /** Signed with the key, and new. */
        ACCEPTED,
        /** Not signed. */
        UNSIGNED,
        /** Signed, but not with this key (or changed on the way). */
        WRONG_SIGNATURE,
        /** Its timestamp is not above the last one of its stream: a replay or a duplicate. */
        REPLAYED,
        /** The first of a stream, more than a minute older than this receiver's time. */
        TOO_OLD
    }

    private final SigningKey key;
    private final InstantSource clock;
    private final Map<Long, Long> streams = new LinkedHashMap<>(16, 0.75f, true) {
        @Override
        protected boolean removeEldestEntry(Map.Entry<Long, Long> eldest) {
            return size() > MAX_STREAMS;
        }
    };
    private long local;

    /**
     * @param key   the shared secret key
     * @param clock the wall clock
     */
    public SignatureCheck(SigningKey key, InstantSource clock) {
        this.key = Objects.requireNonNull(key, "key");
        this.clock = Objects.requireNonNull(clock, "clock");
    }

    /** @return the key */
    public SigningKey key() {
        return key;
    }

    /**
     * @param frame a frame
     * @return what its signature says; only {@link Verdict#ACCEPTED} advances its stream
     */
    public Verdict check(Frame frame) {
        if (!frame.signed()) {
            return Verdict.UNSIGNED;
        }
        if (!signatureMatches(frame)) {
            return Verdict.WRONG_SIGNATURE;
        }
        Frame.Signature s = frame.signature().orElseThrow();
        long stream = (long) frame.systemId() << 16 | (long) frame.componentId() << 8 | s.linkId();
        synchronized (this) {
            local = Math.max(local, SigningTime.of(clock.instant()));
            Long last = streams.get(stream);
            if (last == null) {
                if (s.timestamp() + SigningTime.ONE_MINUTE < local) {
                    return Verdict.TOO_OLD;
                }
            } else if (s.timestamp() <= last) {
                return Verdict.REPLAYED;
            }
            streams.put(stream, s.timestamp());
            local = Math.max(local, s.timestamp());
            return Verdict.ACCEPTED;
        }
    }

    /**
     * @param frame a signed frame
     * @return whether its signature was made with this key (timestamps not checked)
     */
    public boolean signatureMatches(Frame frame) {
        Frame.Signature s = frame.signature().orElse(null);
        if (s == null) {
            return false;
        }
        byte[] covered = frame.signedBytes();
        return MessageDigest.isEqual(key.signature(covered, 0, covered.length), s.value());
    }
}
