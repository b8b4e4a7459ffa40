package io.robomw.agents.host;

import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.PeerException;
import io.robomw.agents.host.rmi.PeerLink;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.agents.messaging.TestKeys;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.junit.jupiter.api.io.TempDir;

import javax.net.ssl.SSLContext;
import java.nio.file.Path;
import java.security.SecureRandom;
import java.time.Duration;

import java.util.List;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Agent protocol version 3 (docs/agents.md, "Wire and store formats"): hops go on the hosts' agent
 * wire, plain and TLS, with every other call still over RMI; a host of a build before the wire
 * (version 2 only) still takes agents from hosts of this build and sends them to them, over RMI.
 */
class AgentWireTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("agent wire test");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    private AgentHost start(AgentHostBuilder b) throws Exception {
        return hosts.start(b);
    }


    @Test
    void hopsGoOnTheWireAndTheStateArrivesWhole() throws Exception {
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging());
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging());
        AgentHost b = start(AgentHost.builder("b").clusterKey(KEY).noMessaging());
        assertTrue(a.wirePort() > 0 && b.wirePort() > 0 && a.wirePort() != b.wirePort(), a.wirePort() + " " + b.wirePort());
        // 600 kB: more than the unproven limit, and written in several pieces (WireWriter.ONE_WRITE)
        VisitorAgent agent = new VisitorAgent().payload(600_000);
        agent.itinerary().addStop(a.address()).addStop(b.address()).addStop(a.address()).addStop(home.address());
        assertEquals(List.of("a", "b", "a", "home"), home.agency().startTrip(agent).result().get(20, TimeUnit.SECONDS));
        // A first arrival is answered NEED_ARCHIVE, the archive goes over RMI, and the transfer comes again: 2 + 1 at a.
        assertEquals(3, a.wireFramesServed(), "both arrivals at a came on its wire");
        assertEquals(2, b.wireFramesServed());
        // The news that it arrived at b and at a (hosts the home did not send it to), then its transfer home;
        // the news from a may come after the result.
        homeWireServes(home, 3);
    }

    /** Waits until a home's wire has served {@code n} frames (arrival news comes on its own time), and checks it served no more. */
    private static void homeWireServes(AgentHost home, int n) {
        Await.until("home's wire served " + n + " frames", Duration.ofSeconds(30), () -> home.wireFramesServed() >= n,
                () -> home.wireFramesServed() + " frames");
        assertEquals(n, home.wireFramesServed());
    }

    @Test
    void aWireWhoseAcceptThreadFailsStopsListeningAndAgentsHopOverRmi() throws Exception {
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging());
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging().wireThreads(r -> {
            throw new OutOfMemoryError("unable to create native thread (test)");
        }));
        int port = a.wirePort();
        VisitorAgent first = new VisitorAgent().payload(20_000);
        first.itinerary().addStop(a.address()).addStop(home.address());
        assertEquals(List.of("a", "home"), home.agency().startTrip(first).result().get(20, TimeUnit.SECONDS), "the agent still reached a, over RMI");
        assertInstanceOf(OutOfMemoryError.class, a.wireFailure(), "the failure is kept for the host's operator");
        assertEquals(0, a.wireFramesServed());
        assertThrows(java.net.ConnectException.class, () -> new java.net.Socket("127.0.0.1", port).close(),
                "the wire no longer listens, so peers are refused at once rather than left waiting");
        VisitorAgent second = new VisitorAgent().payload(20_000);
        second.itinerary().addStop(a.address()).addStop(home.address()).addStop(a.address()).addStop(home.address());
        assertEquals(List.of("a", "home", "a", "home"), home.agency().startTrip(second).result().get(20, TimeUnit.SECONDS), "and a keeps serving");
    }

    @Test
    void durableHostsHopOnTheWireAndKeepNothingOnceTheAgentIsHome(@TempDir Path dir) throws Exception {
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging().store(dir.resolve("home")));
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging().store(dir.resolve("a")));
        VisitorAgent agent = new VisitorAgent().payload(300_000);
        agent.itinerary().addStop(a.address()).addStop(home.address()).addStop(a.address()).addStop(home.address());
        assertEquals(List.of("a", "home", "a", "home"), home.agency().startTrip(agent).result().get(20, TimeUnit.SECONDS));
        assertEquals(3, a.wireFramesServed(), "both arrivals at a (the first asked for the archive) came on its wire");
        AgentHostTest.await(() -> a.agents().isEmpty());
    }

    @Test
    void hopsGoOnTheWireOverTlsBetweenHostsWithCertificatesAlone(@TempDir Path dir) throws Exception {
        TestKeys keys = TestKeys.create(dir);
        SSLContext before = SSLContext.getDefault();
        // RMI's client sockets use the JVM's default context (a factory in a stub cannot carry keys); the wire uses the host's own.
        SSLContext.setDefault(keys.node().context());
        try {
            AgentHost home = start(AgentHost.builder("home").tls(keys.node()).noMessaging());
            AgentHost a = start(AgentHost.builder("a").tls(keys.node()).noMessaging());
            VisitorAgent agent = new VisitorAgent().payload(300_000);
            agent.itinerary().addStop(a.address()).addStop(home.address()).addStop(a.address());
            assertEquals(List.of("a", "home", "a"), home.agency().startTrip(agent).result().get(30, TimeUnit.SECONDS));
            assertEquals(3, a.wireFramesServed(), "both arrivals at a (the first asked for the archive) came on its TLS wire");
            assertEquals(1, home.wireFramesServed(), "the transfer home (no news: the agent went only to a, from home, and home)");
        } finally {
            SSLContext.setDefault(before);
        }
    }

    @Test
    void aHostOfABuildBeforeTheWireTakesAndSendsAgentsOverRmi() throws Exception {
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging().olderHosts());
        AgentHost old = start(AgentHost.builder("old").clusterKey(KEY).noMessaging().version2Only());
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging().olderHosts());
        assertEquals(0, old.wirePort(), "a version-2 host offers no wire");
        VisitorAgent agent = new VisitorAgent().payload(100_000);
        agent.itinerary().addStop(old.address()).addStop(a.address()).addStop(home.address());
        assertEquals(List.of("old", "a", "home"), home.agency().startTrip(agent).result().get(20, TimeUnit.SECONDS));
        assertEquals(0, a.wireFramesServed(), "the version-2 host sent the agent to a over RMI");
        homeWireServes(home, 2); // a's news that the agent arrived there, and the transfer home: on home's wire
        assertTrue(old.refused() >= 1, "the old host refused home's version-4 and 3 authentications, naming its version");

        PeerLink unbound = new PeerLink(HostAddress.parse(old.address()), "probe", KEY, new HostSockets.Client("127.0.0.1", false, 10_000),
                new SecureRandom());
        PeerException refused = assertThrows(PeerException.class, () -> unbound.call(Op.LIST, new byte[0]),
                "a link not told it may talk to older builds does not fall back to a version that does not bind the channel");
        assertTrue(refused.getMessage().contains("does not speak agent protocol version 4"), refused.getMessage());
        PeerLink toOld = new PeerLink(HostAddress.parse(old.address()), "probe", KEY, new HostSockets.Client("127.0.0.1", false, 10_000), new SecureRandom());
        toOld.olderHosts();
        assertEquals(Reply.Status.OK, toOld.call(Op.LIST, new byte[0]).status());
        assertEquals(Session.PROTOCOL_VERSION, toOld.version(), "the link fell back to version 2");
        assertEquals(0, toOld.wirePort());
        PeerLink oldPeer = new PeerLink(HostAddress.parse(a.address()), "old-peer", KEY, new HostSockets.Client("127.0.0.1", false, 10_000),
                new SecureRandom());
        oldPeer.proposeVersion2Only();
        assertEquals(Reply.Status.OK, oldPeer.call(Op.LIST, new byte[0]).status());
        assertEquals(Session.PROTOCOL_VERSION, oldPeer.version(), "a host of this build takes version 2 from an old peer");
        PeerLink toNew = new PeerLink(HostAddress.parse(a.address()), "probe", KEY, new HostSockets.Client("127.0.0.1", false, 10_000), new SecureRandom());
        assertEquals(Reply.Status.OK, toNew.call(Op.LIST, new byte[0]).status());
        assertEquals(Session.COMPACT_VERSION, toNew.version());
        assertEquals(a.wirePort(), toNew.wirePort(), "the answer names the host's wire port");
    }

    @Test
    void aHostOfABuildBeforeTheCompactFormGetsAgentsInTheStandardFormWithoutLeave() throws Exception {
        // no olderHosts(): a host of version 4 binds the channel as one of 5 does
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging());
        AgentHost old = start(AgentHost.builder("old").clusterKey(KEY).noMessaging().beforeCompactForm());
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging());
        VisitorAgent agent = new VisitorAgent().payload(10_000);
        agent.itinerary().addStop(a.address()).addStop(old.address()).addStop(a.address()).addStop(old.address()).addStop(home.address());
        assertEquals(List.of("a", "old", "a", "old", "home"), home.agency().startTrip(agent).result().get(20, TimeUnit.SECONDS),
                "the old host read the agent a sent it, before and after their session was made (it refuses the compact form, as builds"
                        + " before it did), and a read the one it sent back");
        assertTrue(old.wireFramesServed() >= 1, "on the old host's agent wire");

        PeerLink toOld = new PeerLink(HostAddress.parse(old.address()), "probe", KEY, new HostSockets.Client("127.0.0.1", false, 10_000), new SecureRandom());
        assertEquals(Reply.Status.OK, toOld.call(Op.LIST, new byte[0]).status());
        assertEquals(Session.BOUND_VERSION, toOld.version(), "the link fell back from 5 to 4 by itself");
        assertEquals(old.wirePort(), toOld.wirePort());
    }

    @Test
    void aHostWithItsWireOffTakesAndSendsAgentsOverRmi() throws Exception {
        AgentHost home = start(AgentHost.builder("home").clusterKey(KEY).noMessaging());
        AgentHost off = start(AgentHost.builder("off").clusterKey(KEY).noMessaging().wire(false));
        AgentHost a = start(AgentHost.builder("a").clusterKey(KEY).noMessaging());
        assertEquals(0, off.wirePort());
        VisitorAgent agent = new VisitorAgent().payload(100_000);
        agent.itinerary().addStop(off.address()).addStop(a.address()).addStop(home.address());
        assertEquals(List.of("off", "a", "home"), home.agency().startTrip(agent).result().get(20, TimeUnit.SECONDS));
        assertEquals(0, a.wireFramesServed(), "the host with its wire off sent the agent to a over RMI");
        homeWireServes(home, 2); // a's news that the agent arrived there, and the transfer home: on home's wire
        PeerLink toOff = new PeerLink(HostAddress.parse(off.address()), "probe", KEY, new HostSockets.Client("127.0.0.1", false, 10_000), new SecureRandom());
        assertEquals(Reply.Status.OK, toOff.call(Op.LIST, new byte[0]).status());
        assertEquals(Session.COMPACT_VERSION, toOff.version(), "it speaks version 5");
        assertEquals(0, toOff.wirePort(), "and offers no wire");
    }
}
