package io.robomw.agents.host.rmi;

import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.StartedHosts;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.net.OwnerThreads;
import io.robomw.api.spi.FailurePolicy;
import io.robomw.testkit.Await;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import java.security.SecureRandom;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CyclicBarrier;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** A link's agent wire connections under a sustained load of concurrent calls, and once it falls quiet. */
class WireReuseTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("test cluster");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();
    private final ExecutorService tagger = Executors.newCachedThreadPool(new OwnerThreads("wire-reuse-test-tag", FailurePolicy.logging()));
    private final ExecutorService callers = Executors.newFixedThreadPool(PeerLink.MAX_WIRES, new OwnerThreads("wire-reuse-test-call", FailurePolicy.logging()));
    private PeerLink link;

    @AfterEach
    void close() throws InterruptedException {
        callers.shutdownNow();
        if (link != null) {
            link.close();
        }
        tagger.shutdownNow();
        assertTrue(callers.awaitTermination(30, TimeUnit.SECONDS) && tagger.awaitTermination(30, TimeUnit.SECONDS), "the test's threads ended");
    }

    @Test
    void aSustainedLoadReusesItsConnectionsAndAQuietLinkKeepsOnlyAFew() throws Exception {
        AgentHost b = hosts.start(AgentHost.builder("b").clusterKey(KEY).noMessaging());
        link = new PeerLink(HostAddress.parse(b.address()), "probe", KEY, new HostSockets.Client("127.0.0.1", false, 10_000), new SecureRandom(), null,
                10_000);
        link.wireTagger(tagger);
        // News of an agent b never sent: b answers OK and drops it. ARRIVALS go on the wire.
        byte[] news = Bodies.arrivals(List.of(new Bodies.Arrival(UUID.randomUUID(), "rmi://127.0.0.1:1/x")));
        int rounds = 100;
        CyclicBarrier together = new CyclicBarrier(PeerLink.MAX_WIRES);
        List<CompletableFuture<Void>> done = new ArrayList<>();
        for (int t = 0; t < PeerLink.MAX_WIRES; t++) {
            done.add(CompletableFuture.runAsync(() -> {
                try {
                    for (int r = 0; r < rounds; r++) {
                        together.await(30, TimeUnit.SECONDS); // each round, all of them call at once
                        assertEquals(Reply.Status.OK, link.call(Op.ARRIVALS, news).status());
                    }
                } catch (Exception e) {
                    throw new IllegalStateException(e);
                }
            }, callers));
        }
        CompletableFuture.allOf(done.toArray(CompletableFuture[]::new)).get(120, TimeUnit.SECONDS);
        assertTrue(link.wiresOpened() >= 1, "the calls went on the agent wire");
        // Rounds of up to MAX_WIRES calls at once: closing those past MAX_IDLE_WIRES after each call opened hundreds.
        assertTrue(link.wiresOpened() <= 3L * PeerLink.MAX_WIRES, "the load reused its connections: " + link.wiresOpened() + " opened for "
                + rounds + " rounds of " + PeerLink.MAX_WIRES + " calls at once");
        Await.until("the quiet link keeps at most " + PeerLink.MAX_IDLE_WIRES + " idle connections", Duration.ofSeconds(30),
                () -> link.idleWireCount() <= PeerLink.MAX_IDLE_WIRES, () -> link.idleWireCount() + " idle");
    }
}
