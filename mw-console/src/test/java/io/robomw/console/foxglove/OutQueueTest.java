package io.robomw.console.foxglove;

import org.junit.jupiter.api.Test;

import java.nio.ByteBuffer;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A client's queue: bounded, the oldest data dropped first, control never dropped and sent first. */
class OutQueueTest {

    private static OutQueue.Frame data(int i) {
        return OutQueue.Frame.binary(ByteBuffer.allocate(4).putInt(0, i));
    }

    @Test
    void aFullDataQueueDropsItsOldestFrame() {
        OutQueue q = new OutQueue(4, 4);
        for (int i = 0; i < 10; i++) {
            q.offerData(data(i));
        }
        assertEquals(4, q.size());
        assertEquals(6, q.dropped());
        for (int i = 6; i < 10; i++) {
            assertEquals(i, q.poll().binary().getInt(0));
        }
        assertNull(q.poll());
    }

    @Test
    void controlFramesGoOutBeforeDataQueuedEarlier() {
        OutQueue q = new OutQueue(4, 4);
        q.offerData(data(1));
        assertTrue(q.offerControl(OutQueue.Frame.text("advertise")));
        assertEquals("advertise", q.poll().text());
        assertEquals(1, q.poll().binary().getInt(0));
    }

    @Test
    void aFullControlQueueRefusesRatherThanDrop() {
        OutQueue q = new OutQueue(4, 2);
        assertTrue(q.offerControl(OutQueue.Frame.text("a")));
        assertTrue(q.offerControl(OutQueue.Frame.text("b")));
        assertFalse(q.offerControl(OutQueue.Frame.text("c")));
        assertEquals("a", q.poll().text());
        assertEquals(0, q.dropped());
    }
}
