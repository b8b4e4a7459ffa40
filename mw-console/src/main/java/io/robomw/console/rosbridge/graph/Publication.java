package io.robomw.console.rosbridge.graph;

import com.fasterxml.jackson.databind.node.ObjectNode;
import io.robomw.console.rosbridge.msg.Wire;

import java.util.LinkedHashMap;
import java.util.Map;

/**
 * One message published on a topic, on its way to every subscriber. Its {@code publish} frame is
 * written at most once per wire form (JSON text, CBOR bytes), however many clients get it, and
 * only when a client asks for that form. The tree must not change after publishing. Thread-safe.
 */
public final class Publication {

    private final String topic;
    private final ObjectNode msg;
    private final long publishedNanos;
    private volatile String json;
    private volatile byte[] cbor;

    /**
     * @param topic          the topic's name
     * @param msg            the message
     * @param publishedNanos when, on the {@link System#nanoTime()} clock
     */
    public Publication(String topic, ObjectNode msg, long publishedNanos) {
        this.topic = topic;
        this.msg = msg;
        this.publishedNanos = publishedNanos;
    }

    /** @return the topic's name */
    public String topic() {
        return topic;
    }

    /** @return the message; do not change it */
    public ObjectNode msg() {
        return msg;
    }

    /** @return when it was published, {@link System#nanoTime()} */
    public long publishedNanos() {
        return publishedNanos;
    }

    /** @return {@code {"op":"publish","topic":...,"msg":...}} as JSON text (NaN as null, bytes as base64) */
    public String jsonFrame() {
        String j = json;
        if (j == null) {
            j = Wire.jsonFrame(frame(topic));
            json = j;
        }
        return j;
    }

    /**
     * @param clientTopic the topic's name as a client wrote it, if not as {@link #topic()} is
     * @return the frame with that name
     */
    public String jsonFrame(String clientTopic) {
        return clientTopic.equals(topic) ? jsonFrame() : Wire.jsonFrame(frame(clientTopic));
    }

    /** @return the same frame as one CBOR map (a binary frame: {@code compression: cbor}) */
    public byte[] cborFrame() {
        byte[] c = cbor;
        if (c == null) {
            c = Wire.cborFrame(frame(topic));
            cbor = c;
        }
        return c;
    }

    /**
     * @param clientTopic the topic's name as a client wrote it
     * @return the CBOR frame with that name
     */
    public byte[] cborFrame(String clientTopic) {
        return clientTopic.equals(topic) ? cborFrame() : Wire.cborFrame(frame(clientTopic));
    }

    private Map<String, Object> frame(String name) {
        Map<String, Object> f = new LinkedHashMap<>();
        f.put("op", "publish");
        f.put("topic", name);
        f.put("msg", msg);
        return f;
    }
}
