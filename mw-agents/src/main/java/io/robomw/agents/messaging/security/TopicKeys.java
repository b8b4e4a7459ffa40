package io.robomw.agents.messaging.security;

import javax.crypto.SecretKey;
import javax.crypto.SecretKeyFactory;
import javax.crypto.spec.PBEKeySpec;
import javax.crypto.spec.SecretKeySpec;
import java.nio.charset.StandardCharsets;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import java.util.LinkedHashMap;
import java.util.Map;

/**
 * Derives the HMAC key of a password-protected topic: PBKDF2-HMAC-SHA256 over the password,
 * salted with the topic name, {@value #ITERATIONS} iterations, 256 bits. The salt makes the same
 * password give different keys on different topics; the iterations make guessing a password from
 * captured frames slow. Derived keys are cached (the derivation takes milliseconds).
 *
 * <p>Thread-safe. One instance per messaging node.
 */
public final class TopicKeys {

    /** PBKDF2 iterations. Changing it changes every key: all nodes must agree. */
    public static final int ITERATIONS = 20_000;
    private static final int CACHE_SIZE = 256;

    private final Map<Map.Entry<String, String>, SecretKey> cache = new LinkedHashMap<>(16, 0.75f, true) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<Map.Entry<String, String>, SecretKey> eldest) {
            return size() > CACHE_SIZE;
        }
    };

    /**
     * @param topic    the topic
     * @param password its password, or {@code null} for an open topic
     * @return the topic's HMAC key, or {@code null} for an open topic
     */
    public SecretKey key(String topic, String password) {
        if (password == null) {
            return null;
        }
        Map.Entry<String, String> id = Map.entry(topic, password);
        synchronized (cache) {
            SecretKey key = cache.get(id);
            if (key == null) {
                key = derive(topic, password);
                cache.put(id, key);
            }
            return key;
        }
    }

    /**
     * @param a a key or {@code null}
     * @param b a key or {@code null}
     * @return whether both are open, or both are the same key (compared in constant time)
     */
    public static boolean same(SecretKey a, SecretKey b) {
        if (a == null || b == null) {
            return a == b;
        }
        return MessageDigest.isEqual(a.getEncoded(), b.getEncoded());
    }

    private static SecretKey derive(String topic, String password) {
        try {
            PBEKeySpec spec = new PBEKeySpec(password.toCharArray(), ("robomw-topic:" + topic).getBytes(StandardCharsets.UTF_8), ITERATIONS, 256);
            try {
                byte[] raw = SecretKeyFactory.getInstance("PBKDF2WithHmacSHA256").generateSecret(spec).getEncoded();
                return new SecretKeySpec(raw, "HmacSHA256");
            } finally {
                spec.clearPassword();
            }
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK cannot derive topic keys (PBKDF2WithHmacSHA256): " + e, e);
        }
    }
}
