package io.robomw.agents.host.home;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.protocol.AgentEvent;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.messaging.MessagingNode;
import io.robomw.api.Message;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.HexFormat;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.BiFunction;

/**
 * Agent events (reports, results, failures, arrivals) to a home through an MQTT broker, for a
 * home announced at a broker this host's node is at: the home may be out of direct reach (behind
 * NAT), or away for a while. With a persistent session ({@code ?session-expiry=...} on the
 * home's messaging address) the broker keeps the events for a home that is away, and it gets
 * them when it is back.
 *
 * <p>An event is a request on the reserved topic {@value #TOPIC}, to the home's node (named as
 * the home host), signed with a password derived from the cluster key (only cluster members can
 * send or accept one), carrying {@link AgentEvent#encode()}; the home answers {@code "ok"} once it
 * has handled it. An event whose answer has not come within {@link #ANSWER} is not sent again at
 * each retry of {@link HomeEvents} (that would queue copies at the broker for an absent home):
 * the retry waits for the answer to the request already sent, and sends again only after
 * {@link #RESEND} without an answer. The home drops duplicates (reports by sequence number).
 *
 * <p>Thread-safe.
 */
public final class BrokerEvents {

    private static final Logger LOG = LoggerFactory.getLogger(BrokerEvents.class);
    /** The topic agent events travel on (reserved: agents cannot use it with another password). */
    static final String TOPIC = "robomw/agent-events";
    /** How long one delivery attempt waits for the home's answer. */
    static final Duration ANSWER = Duration.ofSeconds(2);
    /** After how long without an answer an event is sent again. */
    static final Duration RESEND = Duration.ofSeconds(60);
    private static final int MAX_OUTSTANDING = 100_000;

    private record Sent(UUID correlation, long atNanos) {
    }

    private final MessagingNode node;
    private final String password;
    private final String hostName;
    private final Map<String, Sent> outstanding = new ConcurrentHashMap<>();

    /**
     * @param node     the host's node
     * @param key      the cluster key
     * @param hostName the host's name, for logs
     */
    public BrokerEvents(MessagingNode node, ClusterKey key, String hostName) {
        this.node = node;
        this.password = HexFormat.of().formatHex(key.mac("robomw agent events 1".getBytes(StandardCharsets.UTF_8)));
        this.hostName = hostName;
    }

    /**
     * Delivers one event to a home through a broker; returns once the home answered.
     *
     * @param broker the broker's address (the node is there)
     * @param home   the home's agent host address
     * @param event  the event
     * @throws IOException if the home did not answer within {@link #ANSWER} (the event may be at the
     *                     broker, waiting for it) or refused it
     */
    public void deliver(String broker, String home, AgentEvent event) throws IOException {
        String key = event.id() + "/" + event.seq() + "/" + event.kind() + "/" + event.location();
        Sent sent = outstanding.get(key);
        if (sent == null || System.nanoTime() - sent.atNanos() > RESEND.toNanos()) {
            UUID id = node.sendMessage(HostAddress.parse(home).name(), broker, password, TOPIC, event.encode(), "event");
            sent = new Sent(id, System.nanoTime());
            if (outstanding.size() >= MAX_OUTSTANDING) {
                outstanding.clear();
            }
            outstanding.put(key, sent);
        }
        Message answer;
        try {
            answer = node.waitForReply(sent.correlation(), ANSWER);
        } catch (RuntimeException e) {
            throw new IOException("home " + home + " has not answered through " + broker + " yet (" + e.getMessage() + ")", e);
        }
        outstanding.remove(key);
        if (!"ok".equals(answer.payload())) {
            throw new IOException("home " + home + " refused the " + event.kind() + " through " + broker + ": " + answer.payload());
        }
        LOG.info("host {}: {} of agent {} delivered to its home {} through broker {}", hostName, event.kind(), event.id(), home, broker);
    }

    /**
     * Receives events for the agents of this home that come through a broker.
     *
     * @param onEvent handles one event ({@code Home#onEvent}): the peer's description and the encoded event
     */
    public void receive(BiFunction<String, byte[], Reply> onEvent) {
        node.addMessageListener(TOPIC, password, m -> {
            if (!(m.payload() instanceof byte[] body)) {
                node.replyMessage(m, "not an agent event", "event");
                return;
            }
            Reply r = onEvent.apply("node '" + m.sender() + "' through a broker", body);
            node.replyMessage(m, r.status() == Reply.Status.OK ? "ok" : r.status() + ": " + r.text(), "event");
        });
    }
}
