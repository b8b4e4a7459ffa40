package io.robomw.agents.messaging.mqtt;

import java.nio.ByteBuffer;
import java.util.ArrayDeque;
import java.util.Iterator;

/**
 * Direct buffers that a broker session hands the MQTT client payloads in. The client sends a
 * direct payload as it is (it wraps it beside the PUBLISH's header) but copies a heap one into a
 * buffer of its own, so a payload copied here once, out of the caller's array, is not copied again;
 * and the buffers are used again once the broker acknowledged their message, instead of a new
 * megabyte array for every camera frame. At most {@code idleBytes} of them wait unused.
 * Thread-safe.
 */
final class PayloadBuffers {

    /** Buffers are made in steps of this many bytes, so that payloads of about one size share them. */
    static final int STEP = 64 * 1024;

    private final long idleBytes;
    private final ArrayDeque<ByteBuffer> idle = new ArrayDeque<>();
    private long idleTotal;

    /** @param idleBytes how many bytes of unused buffers are kept for the next payloads */
    PayloadBuffers(long idleBytes) {
        this.idleBytes = idleBytes;
    }

    /**
     * @param payload bytes to send
     * @return a direct buffer holding a copy of them, from position 0 to their length; {@link #release} it once the
     *         client is done with it
     */
    ByteBuffer copyOf(byte[] payload) {
        ByteBuffer b = take(payload.length);
        b.clear();
        b.put(payload);
        b.flip();
        return b;
    }

    /** @param buffer a buffer from {@link #copyOf}, no longer used by anyone: kept for a next payload, or let go */
    synchronized void release(ByteBuffer buffer) {
        if (idleTotal + buffer.capacity() <= idleBytes) {
            idle.addFirst(buffer);
            idleTotal += buffer.capacity();
        }
    }

    /** @return the bytes of unused buffers kept */
    synchronized long idleBytes() {
        return idleTotal;
    }

    private synchronized ByteBuffer take(int length) {
        for (Iterator<ByteBuffer> it = idle.iterator(); it.hasNext(); ) {
            ByteBuffer b = it.next();
            if (b.capacity() >= length && b.capacity() - length < STEP) {
                it.remove();
                idleTotal -= b.capacity();
                return b;
            }
        }
        return ByteBuffer.allocateDirect((int) Math.min(Integer.MAX_VALUE - 8, ((long) length + STEP - 1) / STEP * STEP));
    }
}
