package io.robomw.agents.messaging.io;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import org.junit.jupiter.api.Test;

import java.io.ByteArrayInputStream;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.ByteBuffer;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** What a stream's peer can make its reader hold: only what it sent, not what it announced. */
class FrameStreamReaderTest {

    private static final int MIB = 1 << 20;

    /** The 8 bytes that announce a frame of {@code length} bytes: magic, version, kind, length. */
    private static byte[] prefix(int length) {
        return ByteBuffer.allocate(FrameCodec.PREFIX_LENGTH).putShort((short) FrameCodec.MAGIC).put((byte) FrameCodec.VERSION)
                .put((byte) 4).putInt(length).array();
    }

    @Test
    void headerAnnouncingAMebibyteHoldsOnlyWhatArrived() throws IOException {
        ByteArrayOutputStream s = new ByteArrayOutputStream();
        s.writeBytes(prefix(MIB));
        s.writeBytes(new byte[100_000]);
        FrameStreamReader r = new FrameStreamReader(new ByteArrayInputStream(s.toByteArray()), MIB);

        FrameException e = assertThrows(FrameException.class, r::next);

        assertEquals(DropReason.TRUNCATED, e.reason());
        // 100 kB arrived: the buffer grew by doubling to hold them, not to the announced megabyte
        assertTrue(r.capacity() <= 2 * 100_008, "buffer of " + r.capacity() + " bytes for 100,008 that arrived");
    }

    @Test
    void aPeerThatSendsOneSmallFrameCostsOnlyTheInitialBuffer() throws Exception {
        byte[] small = new byte[200];
        System.arraycopy(prefix(200), 0, small, 0, FrameCodec.PREFIX_LENGTH);
        FrameStreamReader r = new FrameStreamReader(new ByteArrayInputStream(small), MIB);

        assertEquals(200, r.next());
        assertEquals(FrameStreamReader.INITIAL, r.capacity());
    }

    @Test
    void bufferShrinksBackAfterALargeFrame() throws Exception {
        ByteArrayOutputStream s = new ByteArrayOutputStream();
        byte[] big = new byte[MIB];
        System.arraycopy(prefix(MIB), 0, big, 0, FrameCodec.PREFIX_LENGTH);
        s.writeBytes(big);
        byte[] small = new byte[200];
        System.arraycopy(prefix(200), 0, small, 0, FrameCodec.PREFIX_LENGTH);
        s.writeBytes(small);
        FrameStreamReader r = new FrameStreamReader(new ByteArrayInputStream(s.toByteArray()), MIB);

        assertEquals(MIB, r.next());
        assertEquals(MIB, r.capacity());
        assertEquals(200, r.next());
        assertEquals(FrameStreamReader.STREAMING, r.capacity());
        assertEquals(-1, r.next());
    }

    @Test
    void aStreamOfLargeFramesKeepsOneBufferUntilASmallFrameComes() throws Exception {
        ByteArrayOutputStream s = new ByteArrayOutputStream();
        for (int i = 0; i < 3; i++) {
            byte[] big = new byte[MIB];
            System.arraycopy(prefix(MIB), 0, big, 0, FrameCodec.PREFIX_LENGTH);
            s.writeBytes(big);
        }
        byte[] small = new byte[200];
        System.arraycopy(prefix(200), 0, small, 0, FrameCodec.PREFIX_LENGTH);
        s.writeBytes(small);
        FrameStreamReader r = new FrameStreamReader(new ByteArrayInputStream(s.toByteArray()), MIB);

        assertEquals(MIB, r.next());
        byte[] first = r.buffer();
        assertEquals(MIB, r.next());
        assertEquals(MIB, r.next());
        assertTrue(first == r.buffer(), "the second and third camera frames were read into the first one's buffer");
        assertEquals(200, r.next());
        assertEquals(FrameStreamReader.STREAMING, r.capacity());
    }
}
