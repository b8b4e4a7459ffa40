package io.robomw.agents.messaging.security;

import javax.crypto.Mac;
import javax.crypto.spec.SecretKeySpec;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import java.util.Base64;

/**
 * Signs and checks presence records ({@link io.robomw.agents.messaging.PresenceRecord}) with a key
 * the members of a cluster share (an agent host derives it from the cluster key): HMAC-SHA256
 * over the record's bytes before its {@code sig} line, written as unpadded base64url. A reader
 * with the key ignores (and counts) every record that is unsigned or not signed with it, so
 * nobody without the key can mark a host offline or list a fake one under its name at a broker.
 * Thread-safe.
 */
public final class PresenceSeal {

    private static final String ALGORITHM = "HmacSHA256";

    private final SecretKeySpec key;

    private PresenceSeal(byte[] secret) {
        if (secret == null || secret.length < 16) {
            throw new IllegalArgumentException("a presence key needs at least 16 bytes");
        }
        this.key = new SecretKeySpec(secret.clone(), ALGORITHM);
    }

    /**
     * @param secret the cluster's presence key (at least 16 bytes; an agent host's is derived from its cluster key)
     * @return the seal
     */
    public static PresenceSeal of(byte[] secret) {
        return new PresenceSeal(secret);
    }

    /**
     * @param signed the record's bytes before its {@code sig} line
     * @return the signature, as the {@code sig} line's value
     */
    public String sign(byte[] signed) {
        return Base64.getUrlEncoder().withoutPadding().encodeToString(mac(signed));
    }

    /**
     * @param signed    the record's bytes before its {@code sig} line
     * @param signature the {@code sig} line's value
     * @return whether the signature is this key's over those bytes (constant time)
     */
    public boolean verify(byte[] signed, String signature) {
        byte[] given;
        try {
            given = Base64.getUrlDecoder().decode(signature);
        } catch (IllegalArgumentException e) {
            return false;
        }
        return MessageDigest.isEqual(given, mac(signed));
    }

    private byte[] mac(byte[] bytes) {
        try {
            Mac m = Mac.getInstance(ALGORITHM);
            m.init(key);
            return m.doFinal(bytes);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("HMAC-SHA256 is missing from this JVM", e);
        }
    }
}
