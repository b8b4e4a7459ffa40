package io.robomw.agents.messaging;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

class AddressTest {

    @Test
    void shouldParseEveryScheme() {
        assertEquals(new Address("tcp", "127.0.0.1", 7000, "", java.util.Map.of()), Address.parse("tcp://127.0.0.1:7000"));
        assertEquals("nxt", Address.parse("rmi://127.0.0.1:1099/nxt").path());
        assertEquals("lo", Address.parse("multicast://239.1.2.3:5000?interface=lo&ttl=0").query().get("interface"));
        assertEquals("::1", Address.parse("udp://[::1]:7001").host());
    }

    @Test
    void shouldPrintWithoutTheQuery() {
        assertEquals("multicast://239.1.2.3:5000", Address.parse("multicast://239.1.2.3:5000?ttl=0").toString());
        assertEquals("udp://[::1]:7001", Address.parse("udp://[::1]:7001").toString());
    }

    @Test
    void shouldRejectAnAddressWithoutAPort() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Address.parse("tcp://127.0.0.1"));
        assertEquals(true, e.getMessage().contains("scheme://host:port"));
    }
}
