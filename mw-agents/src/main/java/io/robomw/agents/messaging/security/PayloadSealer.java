package io.robomw.agents.messaging.security;

import javax.crypto.AEADBadTagException;
import javax.crypto.Cipher;
import javax.crypto.Mac;
import javax.crypto.SecretKey;
import javax.crypto.spec.GCMParameterSpec;
import javax.crypto.spec.SecretKeySpec;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.GeneralSecurityException;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Encrypts and decrypts the payloads of password-protected topics with AES-256-GCM, so a
 * subscriber (or a broker, or anyone on the path) that does not know the topic's password reads
 * nothing of them: the paper's "registration of the message listener" with the password is what
 * lets a node read a protected topic.
 *
 * <p>Keys and nonces: each sending node instance (its random 64-bit source id) has a key of its
 * own per topic key, {@code HMAC-SHA256(topic key, "robomw-payload-aes-256-gcm" || source)}, and
 * each of its frames a nonce of its own, {@code [0 0 0 0][message number, 8 bytes]}: a node numbers
 * its frames once each, so no nonce is used twice under one key (NIST SP 800-38D). The sealed
 * payload is the ciphertext followed by the 16-byte tag; the frame's HMAC covers it too.
 * Thread-safe.
 */
public final class PayloadSealer {

    /** Bytes the tag adds to a sealed payload. */
    public static final int TAG_BYTES = 16;
    private static final byte[] LABEL = "robomw-payload-aes-256-gcm".getBytes(StandardCharsets.US_ASCII);
    /** The most (topic key, source) keys kept. */
    private static final int MAX_KEYS = 4096;

    private record KeyOf(SecretKey topicKey, long source) {
    }

    private final Map<KeyOf, SecretKeySpec> keys = new ConcurrentHashMap<>();
    private final ThreadLocal<Cipher> ciphers = ThreadLocal.withInitial(PayloadSealer::newCipher);

    /**
     * @param topicKey the topic's key (from its password)
     * @param source   the sending node's source id
     * @param number   the frame's message number
     * @param plain    the encoded payload
     * @return the sealed payload: ciphertext and tag
     */
    public byte[] seal(SecretKey topicKey, long source, long number, byte[] plain) {
        try {
            Cipher c = ciphers.get();
            c.init(Cipher.ENCRYPT_MODE, key(topicKey, source), nonce(number));
            return c.doFinal(plain);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("AES-GCM failed: " + e.getMessage(), e);
        }
    }

    /**
     * @param topicKey the topic's key
     * @param source   the frame's source id
     * @param number   its message number
     * @param sealed   the sealed payload
     * @return the payload, or {@code null} if it does not decrypt under this key (another password, or changed)
     */
    public byte[] open(SecretKey topicKey, long source, long number, byte[] sealed) {
        if (sealed.length < TAG_BYTES) {
            return null;
        }
        try {
            Cipher c = ciphers.get();
            c.init(Cipher.DECRYPT_MODE, key(topicKey, source), nonce(number));
            return c.doFinal(sealed);
        } catch (AEADBadTagException e) {
            return null;
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("AES-GCM failed: " + e.getMessage(), e);
        }
    }

    private SecretKeySpec key(SecretKey topicKey, long source) {
        KeyOf k = new KeyOf(topicKey, source);
        SecretKeySpec spec = keys.get(k);
        if (spec == null) {
            if (keys.size() >= MAX_KEYS) {
                keys.clear();
            }
            spec = keys.computeIfAbsent(k, PayloadSealer::derive);
        }
        return spec;
    }

    private static SecretKeySpec derive(KeyOf k) {
        try {
            Mac mac = Mac.getInstance("HmacSHA256");
            mac.init(new SecretKeySpec(k.topicKey().getEncoded(), "HmacSHA256"));
            mac.update(LABEL);
            mac.update(ByteBuffer.allocate(8).putLong(k.source()).array());
            return new SecretKeySpec(mac.doFinal(), "AES");
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("HMAC-SHA256 failed: " + e.getMessage(), e);
        }
    }

    private static GCMParameterSpec nonce(long number) {
        return new GCMParameterSpec(TAG_BYTES * 8, ByteBuffer.allocate(12).putInt(0).putLong(number).array());
    }

    private static Cipher newCipher() {
        try {
            return Cipher.getInstance("AES/GCM/NoPadding");
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK has no AES/GCM/NoPadding: " + e, e);
        }
    }
}
