package io.robomw.agents.messaging.mqtt;

import com.hivemq.client.internal.mqtt.message.publish.MqttPublish;
import com.hivemq.client.mqtt.mqtt5.message.publish.Mqtt5Publish;

import java.nio.ByteBuffer;
import java.util.Arrays;

/**
 * The bytes of a received MQTT payload, read where the client put them. The HiveMQ client decodes
 * each PUBLISH's payload into a heap buffer of its own; its public {@link Mqtt5Publish#getPayloadAsBytes()}
 * copies that buffer into a new array (for a 1 MiB frame to 8 subscribers, 8 MiB more to allocate
 * and copy per publication). A node reads a frame only while its {@code onFrame} runs and never
 * writes into it, so the client's own array is read in place; a payload the client keeps any other
 * way (a read-only or direct buffer) is copied, as before.
 *
 * @param array  the bytes (the client's array: read it, never write it, never keep it)
 * @param offset where the payload starts
 * @param length how many bytes it has
 */
record ReceivedPayload(byte[] array, int offset, int length) {

    private static final byte[] EMPTY = new byte[0];

    /**
     * @param publish a received PUBLISH
     * @return its payload, in place where the client keeps it in a writable heap buffer, else copied
     */
    static ReceivedPayload of(Mqtt5Publish publish) {
        // The client's implementation class (com.hivemq.client.internal) gives the buffer itself; its public API only a read-only view.
        if (publish instanceof MqttPublish own) {
            ByteBuffer raw = own.getRawPayload();
            if (raw == null) {
                return new ReceivedPayload(EMPTY, 0, 0);
            }
            if (raw.hasArray()) {
                return new ReceivedPayload(raw.array(), raw.arrayOffset() + raw.position(), raw.remaining());
            }
        }
        byte[] copy = publish.getPayloadAsBytes();
        return new ReceivedPayload(copy, 0, copy.length);
    }

    /**
     * @return the payload as an array of its own: the client's array itself when it holds exactly the
     *         payload (the client made it for this one PUBLISH, hands it to the session's one flow, and
     *         reads it no more), else a copy
     */
    byte[] owned() {
        return offset == 0 && length == array.length ? array : copy();
    }

    /** @return the payload in an array of its own (for what outlives the delivery) */
    byte[] copy() {
        return Arrays.copyOfRange(array, offset, offset + length);
    }
}
