package io.robomw.agents.messaging.spi;

import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.frame.NameBytes;
import org.junit.jupiter.api.Test;

import java.util.Random;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class PublicationTest {

    private static final int MAX = 1 << 22;

    private static Frame scan(int bytes, boolean signed) {
        byte[] payload = new byte[bytes];
        new Random(bytes).nextBytes(payload);
        return new Frame(FrameKind.PUBLISH, 0, 0x1122334455667788L, 42, new UUID(0x1122334455667788L, 42), 1_700_000_000_000_000L,
                "lidar-node", "", "robot-1/scan", "data", 1, payload, signed);
    }

    /** What a receiver rebuilds from the head and the payload is the very publication the whole frame is. */
    @Test
    void theHeadAndThePayloadAreTheWholeFrameWithoutItsPayload() throws FrameException {
        Frame f = scan(Publication.APART_FROM_BYTES, false);
        Publication p = Publication.apart(f, new NameBytes());
        assertTrue(p.travelsApart());
        assertSame(f.payload(), p.payload(), "the payload is not copied");
        Frame head = FrameCodec.decode(p.head(), 0, p.head().length, MAX);
        Frame whole = FrameCodec.decode(p.frame(), 0, p.frame().length, MAX);
        assertEquals(FrameKind.PUBLISH_SHARED, head.kind());
        assertEquals(0, head.payload().length);
        assertEquals(new Frame(FrameKind.PUBLISH, head.streamSequence(), head.source(), head.messageNumber(), head.correlationId(),
                head.timestampMicros(), head.sender(), head.receiver(), head.topic(), head.function(), head.payloadType(), null, false),
                new Frame(whole.kind(), whole.streamSequence(), whole.source(), whole.messageNumber(), whole.correlationId(),
                        whole.timestampMicros(), whole.sender(), whole.receiver(), whole.topic(), whole.function(), whole.payloadType(), null, false));
        assertArrayEquals(f.payload(), whole.payload());
        assertEquals(p.frame().length, p.length(), "its length is the whole frame's, known without encoding it");
        assertArrayEquals(FrameCodec.encode(f, false), p.frame());
    }

    @Test
    void aSignedOrSmallPublicationTravelsWhole() {
        Publication small = Publication.whole(FrameCodec.encode(scan(100, false), false));
        assertFalse(small.travelsApart());
        assertThrows(IllegalStateException.class, small::head);
        assertThrows(IllegalArgumentException.class, () -> Publication.apart(scan(Publication.APART_FROM_BYTES - 1, false), null));
        IllegalArgumentException signed = assertThrows(IllegalArgumentException.class, () -> Publication.apart(scan(1 << 20, true), null));
        assertTrue(signed.getMessage().contains("signed"), signed.getMessage());
    }
}
