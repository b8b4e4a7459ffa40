package io.robomw.agents.host.protocol;

import io.robomw.agents.host.wire.WireReader;
import java.util.ArrayList;
import java.util.List;

/**
 * The arrays a host's large outgoing transfers are written into ({@link Frame.Buffer}), kept for
 * the next ones: an agent of a megabyte hops with a frame of a megabyte, which G1 would otherwise
 * allocate as a humongous object and zero at every hop. An array is taken by one departure and
 * given back once its transfer is over (delivered or not), when nothing reads it any more; only
 * the first {@link Frame#length} bytes of a frame are ever sent or stored, so what an earlier agent
 * left after them stays in this host's memory only. Only arrays of {@value #MIN_BYTES} to
 * {@value #MAX_BYTES} bytes are kept, at most {@value #MAX_KEPT} of them. Thread-safe.
 */
public final class FrameBuffers {

    /** Smaller frames are cheap to allocate: not kept. */
    static final int MIN_BYTES = 64 * 1024;
    /** Larger ones are rare: not kept, so a host does not hold on to many megabytes after one large agent. */
    public static final int MAX_BYTES = WireReader.KEEP_MAX;
    /** The most arrays kept: about as many as departures at once that are worth it. */
    public static final int MAX_KEPT = 4;

    private final List<byte[]> free = new ArrayList<>(MAX_KEPT);

    /**
     * @param bytes the frame length needed
     * @return the smallest kept array of at least that length, no longer kept; {@code null} if none (or the frame is small)
     */
    public synchronized byte[] take(int bytes) {
        if (bytes < MIN_BYTES) {
            return null;
        }
        int best = -1;
        for (int i = 0; i < free.size(); i++) {
            int n = free.get(i).length;
            if (n >= bytes && (best < 0 || n < free.get(best).length)) {
                best = i;
            }
        }
        return best < 0 ? null : free.remove(best);
    }

    /**
     * Keeps an array for a later transfer; the caller must not touch it afterwards.
     *
     * @param array a frame's array whose transfer is over
     */
    public synchronized void give(byte[] array) {
        if (array.length < MIN_BYTES || array.length > MAX_BYTES) {
            return;
        }
        for (byte[] b : free) {
            if (b == array) {
                throw new IllegalStateException("a frame array given back twice");
            }
        }
        if (free.size() < MAX_KEPT) {
            free.add(array);
            return;
        }
        // Full: keep the larger arrays, which are the costly ones to allocate.
        int smallest = 0;
        for (int i = 1; i < free.size(); i++) {
            if (free.get(i).length < free.get(smallest).length) {
                smallest = i;
            }
        }
        if (free.get(smallest).length < array.length) {
            free.set(smallest, array);
        }
    }

    /** @return how many arrays are kept now */
    public synchronized int kept() {
        return free.size();
    }
}
