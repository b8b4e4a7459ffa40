package io.robomw.agents.messaging.mqtt;

import org.junit.jupiter.api.Test;

import java.nio.ByteBuffer;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotSame;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertTrue;

class PayloadBuffersTest {

    @Test
    void aPayloadIsCopiedIntoADirectBufferThatComesBackForTheNextOneOfAboutItsSize() {
        PayloadBuffers buffers = new PayloadBuffers(4 << 20);
        byte[] scan = new byte[100_000];
        scan[0] = 1;
        scan[99_999] = 2;
        ByteBuffer b = buffers.copyOf(scan);
        scan[0] = 9;
        assertTrue(b.isDirect(), "the client sends a direct payload as it is");
        assertEquals(0, b.position());
        assertEquals(100_000, b.remaining());
        assertEquals(1, b.get(0), "a copy: the caller may refill its array");
        assertEquals(2, b.get(99_999));
        buffers.release(b);
        ByteBuffer again = buffers.copyOf(new byte[99_000]);
        assertSame(b, again, "the buffer is used again for a payload of about its size");
        assertEquals(99_000, again.remaining());
        buffers.release(again);
        assertNotSame(b, buffers.copyOf(new byte[1 << 20]), "a payload far larger gets a buffer of its own");
    }

    @Test
    void atMostTheIdleBoundIsKept() {
        PayloadBuffers buffers = new PayloadBuffers(3 * PayloadBuffers.STEP * 2);
        ByteBuffer[] held = new ByteBuffer[5];
        for (int i = 0; i < held.length; i++) {
            held[i] = buffers.copyOf(new byte[100_000]);
        }
        for (ByteBuffer b : held) {
            buffers.release(b);
        }
        assertEquals(3L * PayloadBuffers.STEP * 2, buffers.idleBytes(), "three buffers of 128 KiB kept, two let go");
    }
}
