package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.Address;
import org.junit.jupiter.api.Test;

import java.nio.file.Path;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class MqttTopicsTest {

    private final MqttTopics topics = new MqttTopics("robomw");

    @Test
    void roboMwTopicLevelsBecomeMqttLevels() {
        assertEquals("robomw/pub/robot/nxt-1", topics.publication("robot/nxt-1"));
        assertEquals("robomw/msg/nxt-host", topics.request("nxt-host"));
        assertEquals("robomw/reply/c1", topics.replies("c1"));
        assertEquals("robomw/presence/c1", topics.presence("c1"));
    }

    @Test
    void wildcardsAndPercentAreEscapedSoEveryTopicHasOneMqttTopic() {
        assertEquals("robomw/pub/a%2Bb%23c%25d%00", topics.publication("a+b#c%d\0"));
        assertEquals("a+b#c%d\0", topics.topicOfPublication("robomw/pub/a%2Bb%23c%25d%00"));
        assertEquals("größe/€", topics.topicOfPublication(topics.publication("größe/€")));
    }

    @Test
    void topicsOutsideThePrefixAreNotPublications() {
        assertNull(topics.topicOfPublication("other/pub/x"));
        assertNull(topics.topicOfPublication("robomw/msg/x"));
    }

    @Test
    void aBadEscapeIsRefusedWithTheTopic() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> MqttTopics.unescape("a%2"));
        assertTrue(e.getMessage().contains("a%2"), e.getMessage());
    }

    @Test
    void prefixMayNotHoldWildcardsOrStartWithDollar() {
        assertThrows(IllegalArgumentException.class, () -> new MqttTopics("a/+"));
        assertThrows(IllegalArgumentException.class, () -> new MqttTopics("$SYS"));
        assertThrows(IllegalArgumentException.class, () -> new MqttTopics("lab/"));
        assertEquals("lab/robomw/pub/t", new MqttTopics("lab/robomw").publication("t"));
    }

    @Test
    void optionsComeFromTheAddress() {
        MqttOptions o = MqttOptions.of(Address.parse("mqtts://broker/lab?session-expiry=3600&qos=0&max-queued=5&credentials=/etc/mw/mqtt"), "dispatcher");
        assertTrue(o.tls());
        assertEquals(8883, o.port());
        assertEquals("lab", o.topics().prefix());
        assertEquals(3600, o.sessionExpirySeconds());
        assertEquals(0, o.qos());
        assertEquals(5, o.maxQueued());
        assertEquals(MqttOptions.DEFAULT_MAX_QUEUED_BYTES, o.maxQueuedBytes());
        assertEquals(1L << 20, MqttOptions.of(Address.parse("mqtt://broker?max-queued-bytes=1048576"), "n").maxQueuedBytes());
        assertThrows(IllegalArgumentException.class, () -> MqttOptions.of(Address.parse("mqtt://broker?max-queued-bytes=10"), "n"));
        assertEquals(MqttOptions.DEFAULT_MAX_IN_FLIGHT, o.maxInFlight());
        assertEquals(8, MqttOptions.of(Address.parse("mqtt://broker?max-in-flight=8"), "n").maxInFlight());
        assertThrows(IllegalArgumentException.class, () -> MqttOptions.of(Address.parse("mqtt://broker?max-in-flight=0"), "n"));
        assertEquals("lab-dispatcher", o.clientId(), "a persistent session gets a client id that survives a restart");
        assertEquals(Path.of("/etc/mw/mqtt"), o.credentials());
        assertEquals("mqtts://broker:8883/lab", o.sessionKey());
    }

    @Test
    void aCleanSessionGetsAClientIdOfItsOwn() {
        MqttOptions a = MqttOptions.of(Address.parse("mqtt://127.0.0.1:1883"), "n");
        MqttOptions b = MqttOptions.of(Address.parse("mqtt://127.0.0.1:1883"), "n");
        assertTrue(a.clientId().startsWith("n-"));
        assertTrue(!a.clientId().equals(b.clientId()));
        assertEquals("robomw", a.topics().prefix());
        assertEquals(1, a.qos());
    }

    @Test
    void unknownOrOutOfRangeOptionsAreRefusedByName() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> MqttOptions.of(Address.parse("mqtt://b:1883?qso=1"), "n"));
        assertTrue(e.getMessage().contains("qso"), e.getMessage());
        e = assertThrows(IllegalArgumentException.class, () -> MqttOptions.of(Address.parse("mqtt://b:1883?qos=2"), "n"));
        assertTrue(e.getMessage().contains("qos=2"), e.getMessage());
    }

    @Test
    void credentialsInTheAddressAreRefusedWithoutEchoingThem() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> Address.parse("mqtt://robot:s3cret@broker:1883"));
        assertTrue(!e.getMessage().contains("s3cret"), e.getMessage());
        assertTrue(e.getMessage().contains("file or the environment"), e.getMessage());
    }
}
