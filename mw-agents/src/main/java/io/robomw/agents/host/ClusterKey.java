package io.robomw.agents.host;

import javax.crypto.Mac;
import javax.crypto.SecretKeyFactory;
import javax.crypto.spec.PBEKeySpec;
import javax.crypto.spec.SecretKeySpec;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.util.Arrays;

/**
 * The secret every host of one cluster shares: peers prove they know it (HMAC-SHA256
 * challenge/response) before a host takes anything from them. Derived from a passphrase with
 * PBKDF2-HMAC-SHA256 ({@value #ITERATIONS} iterations), so it can live in a file an operator
 * writes by hand. Immutable.
 */
public final class ClusterKey {

    /** PBKDF2 iterations; every host of a cluster must agree. */
    public static final int ITERATIONS = 20_000;
    /** Length of a truncated MAC on calls between hosts (HMAC-SHA256-128, as RFC 4868 allows). */
    public static final int CALL_MAC_LENGTH = 16;

    /** {@link Mac#getInstance} looks the provider up each time: one instance per thread, initialised per use. */
    private static final ThreadLocal<Mac> MACS = ThreadLocal.withInitial(() -> {
        try {
            return Mac.getInstance("HmacSHA256");
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK has no HmacSHA256", e);
        }
    });

    private final byte[] key;

    private ClusterKey(byte[] key) {
        this.key = key;
    }

    /**
     * @param passphrase the cluster's passphrase
     * @return the key derived from it
     */
    public static ClusterKey fromPassphrase(String passphrase) {
        if (passphrase == null || passphrase.isBlank()) {
            throw new IllegalArgumentException("a cluster passphrase must not be empty");
        }
        PBEKeySpec spec = new PBEKeySpec(passphrase.toCharArray(), "robomw-agent-cluster".getBytes(StandardCharsets.UTF_8), ITERATIONS, 256);
        try {
            return new ClusterKey(SecretKeyFactory.getInstance("PBKDF2WithHmacSHA256").generateSecret(spec).getEncoded());
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK cannot derive keys (PBKDF2WithHmacSHA256): " + e, e);
        } finally {
            spec.clearPassword();
        }
    }

    /**
     * @return the seal of the cluster's presence records at a broker: a key derived from this one
     *         ({@code "robomw-presence"}), so what hosts announce there can be told from a stranger's
     */
    public io.robomw.agents.messaging.security.PresenceSeal presenceSeal() {
        return io.robomw.agents.messaging.security.PresenceSeal.of(mac("robomw-presence".getBytes(java.nio.charset.StandardCharsets.UTF_8)));
    }

    /**
     * For hosts that authenticate peers by mutual TLS alone: a fixed, public key, so the
     * challenge/response proves nothing and the TLS certificates do all the work. Never use it
     * without TLS.
     *
     * @return the TLS-only key
     */
    public static ClusterKey tlsOnly() {
        return new ClusterKey(new byte[32]);
    }

    /**
     * @param file a file holding the passphrase (surrounding white space is ignored)
     * @return the key derived from it
     * @throws IOException naming the file if it cannot be read or is empty
     */
    public static ClusterKey read(Path file) throws IOException {
        String text = Files.readString(file, StandardCharsets.UTF_8).strip();
        if (text.isEmpty()) {
            throw new IOException("cluster key file " + file + " is empty; write a passphrase in it");
        }
        return fromPassphrase(text);
    }

    /**
     * @param parts what to authenticate, in order
     * @return HMAC-SHA256 under the cluster key
     */
    public byte[] mac(byte[]... parts) {
        return hmac(key, parts);
    }

    /**
     * @param key   a key
     * @param parts what to authenticate, in order; each is prefixed with its length so parts cannot run into each other
     * @return HMAC-SHA256 of the parts under the key
     */
    static byte[] hmac(byte[] key, byte[]... parts) {
        try {
            Mac mac = MACS.get();
            mac.init(new SecretKeySpec(key, "HmacSHA256"));
            for (byte[] p : parts) {
                mac.update(new byte[] {(byte) (p.length >>> 24), (byte) (p.length >>> 16), (byte) (p.length >>> 8), (byte) p.length});
                mac.update(p);
            }
            return mac.doFinal();
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK has no HmacSHA256", e);
        }
    }

    @Override
    public String toString() {
        return "ClusterKey[" + Arrays.hashCode(key) % 1000 + "...]";
    }
}
