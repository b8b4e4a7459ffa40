package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.PayloadCodec;
import org.junit.jupiter.api.Test;

import java.nio.ByteBuffer;
import java.util.Arrays;
import java.util.Random;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotSame;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertTrue;

class ReceivedPayloadTest {

    @Test
    void aPayloadInAHeapBufferIsReadInPlaceNotCopied() {
        byte[] frame = frame(1 << 20);
        Mqtt5Publish p = Mqtt5Publish.builder().topic("robomw/pub/scan").payload(frame).build();

        ReceivedPayload got = ReceivedPayload.of(p);

        assertSame(frame, got.array(), "the client's own array, not a 1 MiB copy of it");
        assertEquals(0, got.offset());
        assertEquals(frame.length, got.length());
        assertTrue(FramePeek.isFrame(got.array(), got.offset(), got.length()));
    }

    @Test
    void aPayloadInsideALargerArrayKeepsItsOffsetAndLength() {
        byte[] frame = frame(100_000);
        byte[] larger = new byte[frame.length + 48];
        System.arraycopy(frame, 0, larger, 32, frame.length);
        Mqtt5Publish p = Mqtt5Publish.builder().topic("robomw/pub/scan").payload(ByteBuffer.wrap(larger, 32, frame.length)).build();

        ReceivedPayload got = ReceivedPayload.of(p);

        assertTrue(FramePeek.isFrame(got.array(), got.offset(), got.length()));
        assertArrayEquals(frame, Arrays.copyOfRange(got.array(), got.offset(), got.offset() + got.length()));
        assertArrayEquals(frame, got.copy());
    }

    @Test
    void aReadOnlyPayloadIsCopiedWhole() {
        byte[] frame = frame(4_096);
        Mqtt5Publish p = Mqtt5Publish.builder().topic("robomw/pub/scan").payload(ByteBuffer.wrap(frame).asReadOnlyBuffer()).build();

        ReceivedPayload got = ReceivedPayload.of(p);

        assertNotSame(frame, got.array());
        assertArrayEquals(frame, Arrays.copyOfRange(got.array(), got.offset(), got.offset() + got.length()));
    }

    @Test
    void noPayloadIsEmptyAndNoFrame() {
        ReceivedPayload got = ReceivedPayload.of(Mqtt5Publish.builder().topic("robomw/pub/scan").build());

        assertEquals(0, got.length());
        assertFalse(FramePeek.isFrame(got.array(), got.offset(), got.length()));
        assertEquals(0, got.copy().length);
    }

    @Test
    void bytesThatOnlyLookLikeAFrameAtAnotherOffsetAreNoFrame() {
        byte[] frame = frame(256);
        byte[] shifted = new byte[frame.length + 1];
        System.arraycopy(frame, 0, shifted, 1, frame.length);

        assertFalse(FramePeek.isFrame(shifted, 0, shifted.length));
        assertTrue(FramePeek.isFrame(shifted, 1, frame.length));
        assertFalse(FramePeek.isFrame(shifted, 1, FrameCodec.HEADER_LENGTH - 1), "shorter than a header");
    }

    private static byte[] frame(int payloadBytes) {
        byte[] payload = new byte[payloadBytes];
        new Random(7).nextBytes(payload);
        Frame f = new Frame(FrameKind.PUBLISH, 0, 1, 1, new UUID(1, 1), 0, "sensor-pub", "", "scan", "data", PayloadCodec.BYTES, payload, false);
        return FrameCodec.encode(f, false);
    }
}
