package io.robomw.console.foxglove;

import com.fasterxml.jackson.databind.node.ArrayNode;
import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.record.Schemas;

import java.util.Collection;
import java.util.List;
import java.util.Map;

/**
 * The server's JSON text messages, in the shapes the Foxglove SDK 0.30.3 sends (its
 * {@code protocol::common::server} types): {@code serverInfo} first, {@code advertise} and
 * {@code unadvertise} of channels, {@code status}. Stateless.
 */
final class ServerMessages {

    /** The capability that lets clients advertise channels and publish on them. */
    static final String CLIENT_PUBLISH = "clientPublish";
    /** The capability that says the server sends its time (TIME frames). */
    static final String TIME = "time";

    private ServerMessages() {
    }

    /**
     * @param name               the server's name, shown by clients
     * @param capabilities       what it offers ({@link #CLIENT_PUBLISH}, {@link #TIME})
     * @param supportedEncodings encodings it takes from publishing clients (empty: none, and the field is left out)
     * @param metadata           facts about the server
     * @param sessionId          changes when the server restarts, so a client knows to forget its state
     */
    static String serverInfo(String name, List<String> capabilities, List<String> supportedEncodings, Map<String, String> metadata, String sessionId) {
        ObjectNode n = Json.MAPPER.createObjectNode();
        n.put("op", "serverInfo");
        n.put("name", name);
        ArrayNode caps = n.putArray("capabilities");
        capabilities.forEach(caps::add);
        if (!supportedEncodings.isEmpty()) {
            ArrayNode enc = n.putArray("supportedEncodings");
            supportedEncodings.forEach(enc::add);
        }
        if (!metadata.isEmpty()) {
            ObjectNode meta = n.putObject("metadata");
            metadata.forEach(meta::put);
        }
        n.put("sessionId", sessionId);
        return Json.write(n);
    }

    /** @param channels channels to advertise @return an {@code advertise} message */
    static String advertise(Collection<Channel> channels) {
        ObjectNode n = Json.MAPPER.createObjectNode();
        n.put("op", "advertise");
        ArrayNode a = n.putArray("channels");
        for (Channel c : channels) {
            ObjectNode e = a.addObject();
            e.put("id", c.id());
            e.put("topic", c.topic());
            e.put("encoding", Schemas.MESSAGE_ENCODING);
            e.put("schemaName", c.schemaName());
            e.put("schema", c.schema());
            e.put("schemaEncoding", Schemas.SCHEMA_ENCODING);
        }
        return Json.write(n);
    }

    /** @param level how bad @param message what happened, for the user @return a {@code status} message */
    static String status(StatusLevel level, String message) {
        ObjectNode n = Json.MAPPER.createObjectNode();
        n.put("op", "status");
        n.put("level", level.code());
        n.put("message", message);
        return Json.write(n);
    }
}
