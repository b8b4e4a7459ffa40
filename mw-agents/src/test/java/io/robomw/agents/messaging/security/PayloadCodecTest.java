package io.robomw.agents.messaging.security;

import org.junit.jupiter.api.Test;

import java.io.Serializable;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class PayloadCodecTest {

    record Point(double x, double y) implements Serializable {
    }

    record Holder(Serializable inside) implements Serializable {
    }

    private final PayloadCodec jdkOnly = new PayloadCodec(PayloadAllowList.jdkDefaults(), getClass().getClassLoader());

    private Serializable roundTrip(PayloadCodec codec, Serializable value) throws PayloadRejectedException {
        PayloadCodec.Encoded e = codec.encode(value);
        return codec.decode(e.type(), e.bytes());
    }

    @Test
    void shouldCarryPlainValuesWithoutSerialization() throws PayloadRejectedException {
        assertNull(roundTrip(jdkOnly, null));
        assertEquals("héllo", roundTrip(jdkOnly, "héllo"));
        assertEquals(42, roundTrip(jdkOnly, 42));
        assertEquals(-7L, roundTrip(jdkOnly, -7L));
        assertEquals(2.5, roundTrip(jdkOnly, 2.5));
        assertEquals(true, roundTrip(jdkOnly, true));
        assertArrayEquals(new byte[] {1, 2}, (byte[]) roundTrip(jdkOnly, new byte[] {1, 2}));
        assertEquals(PayloadCodec.BYTES, jdkOnly.encode(new byte[3]).type());
    }

    @Test
    void shouldCarryJdkValueTypes() throws PayloadRejectedException {
        UUID id = UUID.randomUUID();
        assertEquals(id, roundTrip(jdkOnly, id));
        ArrayList<String> list = new ArrayList<>(List.of("a", "b"));
        assertEquals(list, roundTrip(jdkOnly, list));
        assertEquals(java.time.Instant.ofEpochSecond(5), roundTrip(jdkOnly, java.time.Instant.ofEpochSecond(5)));
        assertEquals(List.of(1, 2, 3), roundTrip(jdkOnly, (Serializable) List.of(1, 2, 3)));
    }

    @Test
    void shouldRejectAnUnknownPayloadTypeCodeNamingIt() {
        PayloadRejectedException e = org.junit.jupiter.api.Assertions.assertThrows(PayloadRejectedException.class, () -> jdkOnly.decode(42, new byte[1]));
        org.junit.jupiter.api.Assertions.assertTrue(e.getMessage().contains("unknown payload type code 42"), e.getMessage());
    }

    @Test
    void shouldRejectAClassNotOnTheAllowList() {
        PayloadRejectedException e = assertThrows(PayloadRejectedException.class, () -> roundTrip(jdkOnly, new Point(1, 2)));
        assertTrue(e.getMessage().contains(Point.class.getName()), e.getMessage());
    }

    @Test
    void shouldAcceptARegisteredClass() throws PayloadRejectedException {
        PayloadCodec codec = new PayloadCodec(PayloadAllowList.jdkDefaults().with(Point.class), getClass().getClassLoader());
        assertEquals(new Point(1, 2), roundTrip(codec, new Point(1, 2)));
    }

    @Test
    void shouldRejectAnUnregisteredClassNestedInARegisteredOne() {
        PayloadCodec codec = new PayloadCodec(PayloadAllowList.jdkDefaults().with(Holder.class), getClass().getClassLoader());
        assertThrows(PayloadRejectedException.class, () -> roundTrip(codec, new Holder(new Point(1, 2))));
    }

    @Test
    void shouldRejectGraphsDeeperThanTheLimit() {
        PayloadCodec codec = new PayloadCodec(PayloadAllowList.jdkDefaults().with(Holder.class), getClass().getClassLoader());
        Serializable deep = "end";
        for (int i = 0; i < PayloadAllowList.MAX_DEPTH + 5; i++) {
            deep = new Holder(deep);
        }
        Serializable tooDeep = deep;
        assertThrows(PayloadRejectedException.class, () -> roundTrip(codec, tooDeep));
    }

    @Test
    void shouldRejectGarbageBytes() {
        assertThrows(PayloadRejectedException.class, () -> jdkOnly.decode(PayloadCodec.SERIALIZED, new byte[] {1, 2, 3}));
        assertThrows(PayloadRejectedException.class, () -> jdkOnly.decode(PayloadCodec.INTEGER, new byte[] {1, 2, 3}));
        assertThrows(PayloadRejectedException.class, () -> jdkOnly.decode(99, new byte[0]));
    }
}
