package io.robomw.agents.host.protocol;

import org.junit.jupiter.api.Test;

import java.util.Arrays;
import java.util.List;
import java.util.UUID;
import java.util.stream.IntStream;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** The ARRIVALS body: what is written is read back, and what breaks its layout is refused saying how. */
class ArrivalsBodyTest {

    @Test
    void arrivalsReadBackInOrder() {
        List<Bodies.Arrival> sent = IntStream.range(0, Bodies.MAX_ARRIVALS)
                .mapToObj(i -> new Bodies.Arrival(UUID.randomUUID(), "rmi://127.0.0.1:" + (1000 + i) + "/héte-" + i)).toList();
        assertEquals(sent, Bodies.readArrivals(Bodies.arrivals(sent)));
    }

    @Test
    void noneOrTooManyAreNotWritten() {
        assertThrows(IllegalArgumentException.class, () -> Bodies.arrivals(List.of()));
        List<Bodies.Arrival> many = IntStream.range(0, Bodies.MAX_ARRIVALS + 1).mapToObj(i -> new Bodies.Arrival(UUID.randomUUID(), "h")).toList();
        assertThrows(IllegalArgumentException.class, () -> Bodies.arrivals(many));
    }

    @Test
    void aBodyCutShortWithBytesLeftOverOrClaimingNoneIsRefused() {
        byte[] body = Bodies.arrivals(List.of(new Bodies.Arrival(UUID.randomUUID(), "rmi://127.0.0.1:1/a"), new Bodies.Arrival(UUID.randomUUID(), "b")));
        String cut = assertThrows(IllegalArgumentException.class, () -> Bodies.readArrivals(Arrays.copyOf(body, body.length - 1))).getMessage();
        assertTrue(cut.contains("cut short"), cut);
        String over = assertThrows(IllegalArgumentException.class, () -> Bodies.readArrivals(Arrays.copyOf(body, body.length + 3))).getMessage();
        assertTrue(over.contains("3 bytes after its 2 arrivals"), over);
        String none = assertThrows(IllegalArgumentException.class, () -> Bodies.readArrivals(new byte[] {0, 0})).getMessage();
        assertTrue(none.contains("claiming 0 arrivals"), none);
        String lying = assertThrows(IllegalArgumentException.class, () -> Bodies.readArrivals(new byte[] {(byte) 0xFF, (byte) 0xFF})).getMessage();
        assertTrue(lying.contains("claiming 65535 arrivals"), lying);
    }
}
