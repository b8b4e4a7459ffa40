package io.robomw.agents.host;

import io.robomw.agents.host.trip.ChatCaller;
import io.robomw.agents.host.trip.ChatResponder;
import io.robomw.testkit.Await;
import io.robomw.api.Agent;
import io.robomw.api.AgentRef;
import io.robomw.api.Messaging;
import io.robomw.api.UnsupportedActionException;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import java.io.Serializable;
import java.time.Duration;

import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/** Agents on different hosts talk through their hosts' messaging nodes, addressing hosts by name. */
class HostMessagingTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("host messaging");
    @RegisterExtension
    final StartedHosts hosts = new StartedHosts();

    private AgentHost host(String name) throws Exception {
        return host(AgentHost.builder(name).clusterKey(KEY));
    }

    private AgentHost host(AgentHostBuilder b) throws Exception {
        return hosts.start(b);
    }


    @Test
    void aHostDescribesItsNameItsMessagingAndTheHostsItKnows() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        home.agency().sendAgent(a.address(), new io.robomw.agents.host.trip.VisitorAgent()).result().get(10, TimeUnit.SECONDS);
        HostDescription d = AgentHost.describe(home.address(), KEY, false);
        assertEquals("home", d.name());
        assertEquals(home.messagingAddresses(), d.messaging());
        assertTrue(d.messaging().get(0).startsWith("tcp://127.0.0.1:"), d.messaging().toString());
        assertEquals(List.of(new HostDescription.Known("a", a.address())), d.known());
    }

    @Test
    void twoAgentsOnTwoHostsExchangeARequestReplyAndAPublicationOnAProtectedTopicByHostName() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        AgentRef responder = home.agency().sendAgent(b.address(), new ChatResponder());
        List<Serializable> reports = new CopyOnWriteArrayList<>();
        responder.addReportListener(reports::add);
        Await.until("the responder listens at b", Duration.ofSeconds(10), () -> reports.contains("ready"));
        AgentRef caller = home.agency().sendAgent(a.address(), new ChatCaller("b"));
        assertEquals("pong from b", caller.result().get(20, TimeUnit.SECONDS));
        assertEquals("heard news from a", responder.result().get(20, TimeUnit.SECONDS));
    }

    @Test
    void anAgentHostsAddressWorksAsTheHostOfAMessageToo() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        AgentHost b = host("b");
        AgentRef responder = home.agency().sendAgent(b.address(), new ChatResponder());
        List<Serializable> reports = new CopyOnWriteArrayList<>();
        responder.addReportListener(reports::add);
        Await.until("the responder listens at b", Duration.ofSeconds(10), () -> reports.contains("ready"));
        assertEquals("pong from b", home.agency().sendAgent(a.address(), new ChatCaller(b.address())).result().get(20, TimeUnit.SECONDS));
        responder.result().get(20, TimeUnit.SECONDS);
    }

    @Test
    void aHostNameNobodyKnowsIsAClearFailureOfTheStop() throws Exception {
        AgentHost home = host("home");
        AgentHost a = host("a");
        ExecutionException e = assertThrows(ExecutionException.class,
                () -> home.agency().sendAgent(a.address(), new ChatCaller("nowhere")).result().get(20, TimeUnit.SECONDS));
        assertTrue(e.getCause().getMessage().contains("no agent host named 'nowhere'"), e.getCause().getMessage());
    }

    @Test
    void aHostWithoutMessagingSaysSoToItsAgents() throws Exception {
        AgentHost home = host("home");
        AgentHost quiet = host(AgentHost.builder("quiet").clusterKey(KEY).noMessaging());
        assertEquals(List.of(), quiet.messagingAddresses());
        Serializable result = home.agency().sendAgent(quiet.address(), new AskMessaging()).result().get(10, TimeUnit.SECONDS);
        assertInstanceOf(String.class, result);
        assertTrue(((String) result).contains("--no-messaging"), (String) result);
    }

    /** Brings home what asking for messaging gave. */
    public static class AskMessaging extends Agent {
        private static final long serialVersionUID = 1L;

        @Override
        public void run() {
            try {
                Messaging m = context().messaging();
                context().setResult("got " + m);
            } catch (UnsupportedActionException e) {
                context().setResult(e.getMessage());
            }
        }
    }
}
