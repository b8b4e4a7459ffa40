package io.robomw.agents.messaging.security;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

class TopicKeysTest {

    @Test
    void shouldDeriveTheSameKeyOnEveryNode() {
        assertTrue(TopicKeys.same(new TopicKeys().key("t", "pw"), new TopicKeys().key("t", "pw")));
    }

    @Test
    void shouldDeriveDifferentKeysForDifferentTopicsOrPasswords() {
        TopicKeys keys = new TopicKeys();
        assertFalse(TopicKeys.same(keys.key("t", "pw"), keys.key("u", "pw")));
        assertFalse(TopicKeys.same(keys.key("t", "pw"), keys.key("t", "pw2")));
    }

    @Test
    void shouldHaveNoKeyForAnOpenTopic() {
        assertNull(new TopicKeys().key("t", null));
        assertTrue(TopicKeys.same(null, null));
        assertFalse(TopicKeys.same(null, new TopicKeys().key("t", "pw")));
    }
}
