package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.mqtt.datatypes.MqttTopic;
import io.robomw.agents.messaging.spi.Channel;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;

/**
 * The way back for one request that came through a broker: its MQTT 5 response topic and
 * correlation data. The node sends the reply (or its refusal) here.
 */
final class ReplyRoute implements Channel {

    private static final Logger LOG = LoggerFactory.getLogger(ReplyRoute.class);

    private final BrokerSession session;
    private final String responseTopic;
    private final byte[] correlation;

    /**
     * @param session       the session the request came on
     * @param responseTopic its response topic, or {@code null} (then it cannot be answered)
     * @param correlation   its correlation data, or {@code null}
     */
    ReplyRoute(BrokerSession session, String responseTopic, byte[] correlation) {
        this.session = session;
        this.responseTopic = responseTopic;
        this.correlation = correlation;
    }

    @Override
    public String peer() {
        return session.peer() + (responseTopic == null ? "" : " (reply to " + responseTopic + ")");
    }

    @Override
    public void send(byte[] frame) throws IOException {
        if (responseTopic == null) {
            LOG.debug("a message through {} came without a response topic; its answer was not sent", session.peer());
            return;
        }
        MqttTopic topic;
        try {
            topic = session.topic(responseTopic);
        } catch (IllegalArgumentException e) {
            throw new IOException("response topic '" + responseTopic + "' is not a topic a reply can be published on: " + e.getMessage(), e);
        }
        session.publish(topic, frame, null, null, correlation);
    }

    @Override
    public int maxFrameBytes() {
        return session.maxFrameBytes();
    }

    @Override
    public boolean isOpen() {
        return session.isOpen();
    }

    @Override
    public boolean isConnection() {
        return true;
    }

    @Override
    public boolean deliversOn(Thread thread) {
        return session.deliversOn(thread);
    }

    @Override
    public void close() {
        // one answer's way back: nothing to close
    }
}
