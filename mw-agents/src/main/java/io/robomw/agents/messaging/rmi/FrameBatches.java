package io.robomw.agents.messaging.rmi;

import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameException;
import io.robomw.agents.messaging.spi.Channel;
import io.robomw.agents.messaging.spi.TransportContext;

/** Splits a batch of frames sent back to back and hands each to the node. */
final class FrameBatches {

    private FrameBatches() {
    }

    /**
     * Frames after garbage cannot be found again, so the rest of such a batch is dropped (once,
     * counted and logged); the session goes on.
     */
    static void deliver(byte[] batch, Channel from, TransportContext context) {
        int at = 0;
        int max = context.settings().maxFrameSize();
        while (at < batch.length) {
            try {
                if (batch.length - at < FrameCodec.PREFIX_LENGTH) {
                    throw new FrameException(io.robomw.agents.messaging.DropReason.TRUNCATED, (batch.length - at) + " stray bytes at the end of a batch");
                }
                int length = FrameCodec.declaredLength(batch, at, max);
                if (length > batch.length - at) {
                    throw new FrameException(io.robomw.agents.messaging.DropReason.TRUNCATED,
                            "frame declares " + length + " bytes, the batch has " + (batch.length - at) + " left");
                }
                context.onFrame(batch, at, length, from);
                at += length;
            } catch (FrameException e) {
                context.dropped(e.reason(), from.peer(), e.getMessage() + "; dropping the rest of the batch");
                return;
            }
        }
    }
}
