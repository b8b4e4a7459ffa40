package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5PayloadFormatIndicator;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;
import io.robomw.agents.messaging.frame.Frame;
import io.robomw.agents.messaging.frame.FrameCodec;
import io.robomw.agents.messaging.frame.FrameKind;
import io.robomw.agents.messaging.security.PayloadCodec;

import java.nio.ByteBuffer;
import java.nio.charset.CharacterCodingException;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.time.Instant;
import java.util.UUID;

/**
 * A publication on a RoboMW topic from a plain MQTT client (a sensor, {@code mosquitto_pub}): its
 * payload is not a RoboMW frame, so it is wrapped in one for the node. It is delivered as text
 * when it is valid UTF-8 (or says it is, with the payload format indicator), else as
 * {@code byte[]}; its sender is {@value #SENDER}. It carries no HMAC, so a password-protected topic
 * drops it ({@code MISSING_MAC}), as it drops any unsigned frame.
 */
final class ForeignPublication {

    /** The sender name of publications from plain MQTT clients. */
    static final String SENDER = "mqtt";

    private ForeignPublication() {
    }

    /**
     * @param topic   the RoboMW topic
     * @param payload the MQTT payload
     * @param publish the MQTT message
     * @return an unauthenticated PUBLISH frame carrying it
     */
    static byte[] frame(String topic, byte[] payload, Mqtt5Publish publish) {
        boolean text = publish.getPayloadFormatIndicator().orElse(Mqtt5PayloadFormatIndicator.UNSPECIFIED) == Mqtt5PayloadFormatIndicator.UTF_8
                || isUtf8(payload);
        Instant now = Instant.now();
        Frame f = new Frame(FrameKind.PUBLISH, 0, 0, 0, new UUID(0, 0), now.getEpochSecond() * 1_000_000L + now.getNano() / 1000,
                SENDER, "", topic, "", text ? PayloadCodec.STRING : PayloadCodec.BYTES, payload, false);
        return FrameCodec.encode(f, false);
    }

    private static boolean isUtf8(byte[] payload) {
        try {
            StandardCharsets.UTF_8.newDecoder().onMalformedInput(CodingErrorAction.REPORT).onUnmappableCharacter(CodingErrorAction.REPORT)
                    .decode(ByteBuffer.wrap(payload));
            return true;
        } catch (CharacterCodingException e) {
            return false;
        }
    }
}
