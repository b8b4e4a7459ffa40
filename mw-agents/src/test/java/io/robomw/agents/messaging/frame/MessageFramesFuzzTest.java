package io.robomw.agents.messaging.frame;

import com.code_intelligence.jazzer.api.FuzzedDataProvider;
import com.code_intelligence.jazzer.junit.FuzzTest;
import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.discovery.BeaconRecord;
import io.robomw.agents.messaging.io.FrameStreamReader;
import io.robomw.agents.messaging.security.PayloadAllowList;
import io.robomw.agents.messaging.security.PayloadCodec;
import io.robomw.agents.messaging.security.PayloadRejectedException;

import java.io.ByteArrayInputStream;
import java.io.EOFException;
import java.io.IOException;

/**
 * Fuzz tests of what a messaging node decodes from the network (docs/fuzzing.md): a datagram or
 * framed stream as one frame, a byte stream cut into frames, a frame's payload, a node's presence
 * and its discovery beacon. The only refusals allowed are {@link FrameException} (with its drop
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
