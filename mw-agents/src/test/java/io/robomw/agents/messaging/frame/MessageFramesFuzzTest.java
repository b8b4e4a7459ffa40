package io.robomw.agents.messaging.frame;

import com.code_intelligence.jazzer.api.FuzzedDataProvider;
import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.discovery.BeaconRecord;
import io.robomw.agents.messaging.mqtt.ApartHead;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.security.PayloadAllowList;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.security.PayloadRejectedException;
import io.robomw.agents.messaging.shm.Handshake;
import io.robomw.agents.messaging.shm.SegmentView;
import io.robomw.agents.messaging.shm.SharedReference;
import io.robomw.agents.messaging.shm.SharedSegment;

import java.io.ByteArrayInputStream;
import java.io.EOFException;
import java.io.IOException;

/**
 * Fuzz tests of what a messaging node decodes from the network (docs/fuzzing.md): a datagram or
 * framed stream as one frame, a byte stream cut into frames, a frame's payload, a node's presence
 * and its discovery beacon, the shared-memory handshake and the references a subscriber takes
 * payloads out of a segment by, the head of a publication whose payload travelled apart through an
 * MQTT broker. The only refusals allowed are {@link FrameException} (with its drop
 * reason), {@link IOException} at the end of a stream, {@link PayloadRejectedException}, and an
 * {@link IllegalArgumentException} from the presence and beacon records.
 */
class MessageFramesFuzzTest {

    private static final int MAX_FRAME = 1 << 16;
    private static final PayloadCodec PAYLOADS = new PayloadCodec(PayloadAllowList.jdkDefaults(), MessageFramesFuzzTest.class.getClassLoader());

    @FuzzTest
    void frame(byte[] input) {
        try {
            FrameCodec.decode(input, 0, input.length, MAX_FRAME);
        } catch (FrameException refused) {
            // the documented refusal
        }
    }

    @FuzzTest
    void stream(byte[] input) {
        FrameStreamReader reader = new FrameStreamReader(new ByteArrayInputStream(input), MAX_FRAME);
        for (int frames = 0; frames < 64; frames++) {
            try {
                int length = reader.next();
                if (length < 0) {
                    return;
                }
                FrameCodec.decode(reader.buffer(), reader.offset(), length, MAX_FRAME);
            } catch (FrameException | EOFException refused) {
                return;
            } catch (IOException e) {
                throw new AssertionError("a stream of bytes in memory failed to read: " + e, e);
            }
        }
    }

    /** What a node announces at a broker, read by every node and {@code mw agents --cluster} from the broker's retained messages. */
    @FuzzTest
    void presence(byte[] input) {
        PresenceRecord p;
        try {
            p = PresenceRecord.decode(input, "fuzz");
        } catch (IllegalArgumentException refused) {
            return;
        }
        if (!PresenceRecord.decode(p.encode(), "fuzz").equals(p)) {
            throw new AssertionError("a presence does not survive its own encoding: " + p);
        }
    }

    /**
     * What a node's discovery beacon says, as {@code Discovery} ({@code mw nodes}, {@code mw topics})
     * reads it from a multicast group: refused naming its sender, or accepted and then written back
     * by its own encoder to the same record, whole (what fitted one datagram fits again).
     */
    @FuzzTest
    void beacon(byte[] input) {
        BeaconRecord b;
        try {
            b = BeaconRecord.decode(input, "fuzz");
        } catch (IllegalArgumentException refused) {
            if (!refused.getMessage().startsWith("fuzz: ")) {
                throw new AssertionError("a refused beacon's error does not name its sender: " + refused.getMessage(), refused);
            }
            return;
        }
        byte[] again = b.encode();
        if (again.length > BeaconRecord.MAX_BYTES || !BeaconRecord.decode(again, "fuzz").equals(b)) {
            throw new AssertionError("a beacon does not survive its own encoding: " + b);
        }
    }

    /**
     * The user property a broker delivers beside a payload that travelled apart from its frame
     * ({@link ApartHead}): refused with {@link FrameException}, or a head the node decodes as it
     * decodes any frame.
     */
    @FuzzTest
    void apartHead(byte[] input) {
        try {
            byte[] head = ApartHead.decode(new String(input, java.nio.charset.StandardCharsets.UTF_8));
            FrameCodec.decode(head, 0, head.length, MAX_FRAME);
        } catch (FrameException refused) {
            // the documented refusal
        }
    }

    /** A shared-memory handshake frame (SHM_ASK, SHM_OFFER, SHM_ACCEPT) as a TCP connection reads it. */
    @FuzzTest
    void handshake(byte[] input) {
        try {
            Frame f = FrameCodec.decode(input, 0, input.length, MAX_FRAME);
            switch (f.kind()) {
                case SHM_ASK -> Handshake.readAsk(f);
                case SHM_OFFER -> Handshake.readOffer(f);
                case SHM_ACCEPT -> Handshake.readAccept(f);
                default -> {
                    // not a handshake frame
                }
            }
        } catch (FrameException refused) {
            // the documented refusal
        }
    }

    /**
     * A PUBLISH_SHARED frame's reference, taken out of a real segment holding one 1,000-byte record
     * by a fresh subscriber view: a reference outside the ring, misaligned, out of order or not
     * matching its record is refused with {@link FrameException}, never read past the mapping.
     */
    @FuzzTest
    void sharedReference(byte[] input) throws IOException {
        SharedSegment segment = Segment.ONE_RECORD;
        try (SegmentView view = SegmentView.open(segment.file().getParent(), new Handshake.Offer(0, segment.nonce(), segment.file()), "fuzz", 4 << 20)) {
            SharedReference ref = SharedReference.read(input, 0, input.length);
            byte[] payload = view.take(ref);
            if (payload.length != 1000) {
                throw new AssertionError("a reference that was taken gave " + payload.length + " bytes, the record holds 1000");
            }
        } catch (FrameException refused) {
            // the documented refusal
        }
    }

    /** One segment for every input, in a temporary folder, with one record in it. */
    private static final class Segment {
        static final SharedSegment ONE_RECORD = make();

        private static SharedSegment make() {
            try {
                java.nio.file.Path dir = java.nio.file.Files.createTempDirectory("robomw-fuzz-shm");
                SharedSegment s = SharedSegment.create(dir, 1 << 20, 4);
                s.file().toFile().deleteOnExit();
                dir.toFile().deleteOnExit();
                SharedSegment.Subscriber cell = s.attach(() -> { });
                cell.activate();
                byte[] publication = FrameCodec.encode(new Frame(FrameKind.PUBLISH, 0, 1, 1, new java.util.UUID(1, 1), 0, "p", "", "t", "f",
                        PayloadCodec.BYTES, new byte[1000], false), false);
                s.send(publication, cell, f -> { }, 1_000_000_000L);
                return s;
            } catch (IOException e) {
                throw new java.io.UncheckedIOException(e);
            }
        }
    }

    @FuzzTest
    void payload(FuzzedDataProvider data) {
        int type = data.consumeInt(0, 255); // the payload type code: 0-7 and 127 are known
        try {
            PAYLOADS.decode(type, data.consumeRemainingAsBytes());
        } catch (PayloadRejectedException refused) {
            // the documented refusal
        }
    }
}
