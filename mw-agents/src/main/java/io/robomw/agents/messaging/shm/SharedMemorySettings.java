package io.robomw.agents.messaging.shm;

/**
 * Whether and how a node sends large publications to subscribers on the same host through shared
 * memory instead of their TCP connections (docs/messaging.md, "Shared memory"). Immutable.
 *
 * @param enabled        whether the node asks for and offers shared memory at all (default on); it never does
 *                       over TLS, nor for frames with an HMAC, whatever this says
 * @param thresholdBytes frames of at least this many bytes go through shared memory (default 64 KiB, where a
 *                       frame is already encoded once for all subscribers); smaller ones stay on TCP
 * @param segmentBytes   the size of the ring in a publisher's segment file, in bytes (default 32 MiB); a node
 *                       makes it at least twice its maximum frame size
 */
public record SharedMemorySettings(boolean enabled, int thresholdBytes, int segmentBytes) {

    /** The default threshold: 64 KiB. */
    public static final int DEFAULT_THRESHOLD = 64 * 1024;
    /** The default ring: 32 MiB. */
    public static final int DEFAULT_SEGMENT = 32 << 20;
    /** The largest ring: 1 GiB (offsets travel as 32-bit numbers). */
    public static final int MAX_SEGMENT = 1 << 30;

    /** Checks the values. */
    public SharedMemorySettings {
        if (thresholdBytes < 1024) {
            throw new IllegalArgumentException("sharedMemory.thresholdBytes must be >= 1024 (a small frame costs less on TCP), got " + thresholdBytes);
        }
        if (segmentBytes < 1 << 20 || segmentBytes > MAX_SEGMENT) {
            throw new IllegalArgumentException("sharedMemory.segmentBytes must be between 1 MiB and 1 GiB, got " + segmentBytes);
        }
    }

    /** @return on, 64 KiB threshold, 32 MiB ring */
    public static SharedMemorySettings defaults() {
        return new SharedMemorySettings(true, DEFAULT_THRESHOLD, DEFAULT_SEGMENT);
    }

    /** @return off: every frame goes over the connection */
    public static SharedMemorySettings off() {
        return new SharedMemorySettings(false, DEFAULT_THRESHOLD, DEFAULT_SEGMENT);
    }

    /** @param on whether it is on @return a copy with that */
    public SharedMemorySettings withEnabled(boolean on) {
        return new SharedMemorySettings(on, thresholdBytes, segmentBytes);
    }

    /** @param bytes the threshold @return a copy with it */
    public SharedMemorySettings withThresholdBytes(int bytes) {
        return new SharedMemorySettings(enabled, bytes, segmentBytes);
    }

    /** @param bytes the ring's size @return a copy with it */
    public SharedMemorySettings withSegmentBytes(int bytes) {
        return new SharedMemorySettings(enabled, thresholdBytes, bytes);
    }
}
