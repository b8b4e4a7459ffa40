package io.robomw.agents.host;

import org.junit.jupiter.api.Test;

import java.io.Closeable;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37: what a host's RMI connections may make it do depends on whether a call on that very
 * connection proved the cluster key, never on the client's address; large calls being read share
 * one budget; connections that proved nothing make way for new ones.
 */
class HostConnectionsTest {

    private final AtomicInteger closed = new AtomicInteger();
    private final Closeable socket = closed::incrementAndGet;

    @Test
    void largeArraysAreReadOnlyOnAConnectionThatProvedTheKeyNotOnAnotherFromTheSameAddress() {
        HostConnections connections = new HostConnections("h", 100 << 20, 0);
        HostConnections.Connection peer = connections.admit("127.0.0.1:5000", socket);
        HostConnections.Connection stranger = connections.admit("127.0.0.1:5001", socket);

        connections.reading(peer);
        assertTrue(connections.mayRead(HostConnections.UNPROVEN_MAX_BYTES), "small calls before any proof (an authentication)");
        assertFalse(connections.mayRead(HostConnections.UNPROVEN_MAX_BYTES + 1), "a large one is refused before it is read");
        connections.proven();
        assertTrue(connections.mayRead(10 << 20), "once a call on the connection proved the key");
        connections.callDone();

        connections.reading(stranger);
        assertFalse(connections.mayRead(10 << 20), "another connection from the same address has proved nothing");
        assertEquals(2, connections.arraysRefused());
    }

    @Test
    void largeCallsBeingReadShareOneBudgetFreedWhenTheyAreDoneOrTheirConnectionCloses() {
        HostConnections connections = new HostConnections("h", 30 << 20, 0);
        List<HostConnections.Connection> proven = new ArrayList<>();
        for (int i = 0; i < 3; i++) {
            HostConnections.Connection c = connections.admit("127.0.0.1:" + (6000 + i), socket);
            connections.reading(c);
            connections.proven();
            proven.add(c);
        }
        connections.reading(proven.get(0));
        assertTrue(connections.mayRead(20 << 20));
        connections.reading(proven.get(1));
        assertFalse(connections.mayRead(20 << 20), "40 MiB would be read at once, above the 30 MiB budget");
        assertTrue(connections.mayRead(10 << 20), "10 MiB more fits");
        assertEquals(30 << 20, connections.reading());
        connections.reading(proven.get(0));
        connections.callDone();
        assertEquals(10 << 20, connections.reading(), "the first call is done");
        connections.closed(proven.get(1));
        assertEquals(0, connections.reading(), "the second's connection closed mid-call");
        connections.reading(proven.get(2));
        assertTrue(connections.mayRead(30 << 20), "the whole budget is free again");
    }

    @Test
    void theOldestConnectionThatProvedNothingMakesWayAndProvenOnesNever() {
        HostConnections connections = new HostConnections("h", 0, 0);
        List<HostConnections.Connection> all = new ArrayList<>();
        for (int i = 0; i < HostConnections.MAX_CONNECTIONS; i++) {
            HostConnections.Connection c = connections.admit("10.0.0.1:" + i, socket);
            if (i % 2 == 0) {
                connections.reading(c);
                connections.proven();
            }
            all.add(c);
        }
        assertNotNull(connections.admit("10.0.0.2:1", socket), "the oldest unproven one (the second) makes way");
        assertEquals(1, closed.get());
        assertEquals(HostConnections.MAX_CONNECTIONS, connections.open());
        for (int i = 1; i < HostConnections.MAX_CONNECTIONS / 2; i++) {
            assertNotNull(connections.admit("10.0.0.2:" + (i + 1), socket));
        }
        // now every open connection is a proven one or one of the new ones; prove the new ones too
        assertEquals(HostConnections.MAX_CONNECTIONS / 2, closed.get(), "every unproven old one made way, no proven one");
        HostConnections full = new HostConnections("h", 0, 0);
        for (int i = 0; i < HostConnections.MAX_CONNECTIONS; i++) {
            full.reading(full.admit("10.0.0.3:" + i, socket));
            full.proven();
        }
        assertNull(full.admit("10.0.0.4:1", socket), "when every open connection proved the key, a new one is refused");
        assertEquals(1, full.refused());
    }
}
