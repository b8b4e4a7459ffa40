package io.robomw.console.rosbridge.protocol;

import com.fasterxml.jackson.databind.JsonNode;
import io.robomw.console.rosbridge.graph.Graph;
import io.robomw.console.rosbridge.graph.TopicResolver;
import io.robomw.console.rosbridge.msg.MessageReader;
import io.robomw.console.rosbridge.msg.Wire;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.LinkedHashMap;
import java.util.Map;

/**
 * What the parts of one client's session share: the graph, how messages are read, the bounds,
 * the client's outbox, and how the client is told about errors.
 */
final class Session {

    private static final Logger LOG = LoggerFactory.getLogger(Session.class);

    final Graph graph;
    final TopicResolver resolver;
    final MessageReader reader;
    final Limits limits;
    final Outbox outbox;
    final String client;
    private volatile StatusLevel statusLevel;
    private long refusals;

    Session(Graph graph, TopicResolver resolver, MessageReader reader, Limits limits, Outbox outbox, String client) {
        this.graph = graph;
        this.resolver = resolver;
        this.reader = reader;
        this.limits = limits;
        this.outbox = outbox;
        this.client = client;
    }

    /** @param level what the client asked for with {@code set_level} */
    void statusLevel(StatusLevel level) {
        statusLevel = level;
    }

    /**
     * Tells the client (only if it asked with {@code set_level}) and the log.
     *
     * @param level how bad
     * @param msg   what happened
     * @param id    the interaction's id, or {@code null}
     */
    void status(StatusLevel level, String msg, JsonNode id) {
        if (level == StatusLevel.ERROR || level == StatusLevel.WARNING) {
            long n;
            synchronized (this) {
                n = ++refusals;
            }
            if (n <= 10 || Long.bitCount(n) == 1) { // a client that sends garbage in a loop is logged, not once per message
                LOG.info("rosbridge: {}{}: {}{}", client, id == null ? "" : " [id " + id + "]", msg, n > 10 ? " (" + n + " refusals so far)" : "");
            }
        } else {
            LOG.debug("rosbridge: {}: {}", client, msg);
        }
        StatusLevel wanted = statusLevel;
        if (wanted != null && level.shownAt(wanted)) {
            Map<String, Object> f = new LinkedHashMap<>();
            f.put("op", "status");
            f.put("level", level.wire());
            f.put("msg", msg);
            if (id != null) {
                f.put("id", id);
            }
            outbox.reply(Wire.jsonFrame(f), null);
        }
    }
}
