package io.robomw.platform.mavlink.wire;

import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.util.Arrays;

/**
 * The 32-byte secret key of MAVLink message signing. RoboMW makes it from a passphrase as
 * MAVProxy's {@code signing setup PASSPHRASE} does: the key is {@code SHA-256(passphrase)} (the
 * passphrase's UTF-8 bytes), so a vehicle set up from MAVProxy and a RoboMW ground station (or the
 * emulator) given the same passphrase sign alike. The passphrase comes from a file or an
 * environment variable, never from a command line or a robot file.
 *
 * <p>Immutable; {@link #toString()} never shows the key.
 */
public final class SigningKey {

    /** Bytes of a key. */
    public static final int LENGTH = 32;

    private final byte[] key;

    private SigningKey(byte[] key) {
        this.key = key;
    }

    /**
     * @param passphrase a passphrase, at least one character
     * @return {@code SHA-256(passphrase)} as the key
     */
    public static SigningKey fromPassphrase(String passphrase) {
        if (passphrase == null || passphrase.isEmpty()) {
            throw new IllegalArgumentException("a signing passphrase must not be empty");
        }
        return new SigningKey(sha256().digest(passphrase.getBytes(StandardCharsets.UTF_8)));
    }

    /**
     * @param key 32 bytes (copied)
     * @return the key
     */
    public static SigningKey of(byte[] key) {
        if (key.length != LENGTH) {
            throw new IllegalArgumentException("a MAVLink signing key has " + LENGTH + " bytes, got " + key.length);
        }
        return new SigningKey(key.clone());
    }

    /** @return the key's bytes (a copy) */
    public byte[] bytes() {
        return key.clone();
    }

    /** @return whether every byte is zero: SETUP_SIGNING with such a key turns signing off */
    public boolean isZero() {
        for (byte b : key) {
            if (b != 0) {
                return false;
            }
        }
        return true;
    }

    /**
     * The signature of a frame: the first 6 bytes of SHA-256(key + the frame up to and including
     * its link id and timestamp).
     *
     * @param signed the bytes the signature covers
     * @param offset where they start
     * @param length how many
     * @return 6 bytes
     */
    byte[] signature(byte[] signed, int offset, int length) {
        MessageDigest d = sha256();
        d.update(key);
        d.update(signed, offset, length);
        return Arrays.copyOf(d.digest(), Framing.SIGNATURE);
    }

    static MessageDigest sha256() {
        try {
            return MessageDigest.getInstance("SHA-256");
        } catch (NoSuchAlgorithmException e) {
            throw new IllegalStateException("this JVM has no SHA-256, which every Java SE has", e);
        }
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof SigningKey k && MessageDigest.isEqual(k.key, key);
    }

    @Override
    public int hashCode() {
        return Arrays.hashCode(key);
    }

    @Override
    public String toString() {
        return "SigningKey[32 bytes, not shown]";
    }
}
