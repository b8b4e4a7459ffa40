package io.robomw.agents.host.code;

import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.util.HexFormat;

/**
 * The code of an agent, as it travels: a jar (zip) of class files, identified by the SHA-256 of
 * its bytes. A host that already has an archive is sent only its digest.
 *
 * @param digest the SHA-256 of {@code bytes}
 * @param bytes  the jar
 */
public record CodeArchive(Digest digest, byte[] bytes) {

    /**
     * @param bytes a jar's bytes
     * @return the archive, its digest computed
     */
    public static CodeArchive of(byte[] bytes) {
        return new CodeArchive(Digest.of(bytes), bytes);
    }

    /**
     * A SHA-256 digest.
     *
     * @param bytes its 32 bytes
     */
    public record Digest(byte[] bytes) {
        /** Length of a digest in bytes. */
        public static final int LENGTH = 32;

        /** Checks the length. */
        public Digest {
            if (bytes.length != LENGTH) {
                throw new IllegalArgumentException("a SHA-256 digest has " + LENGTH + " bytes, not " + bytes.length);
            }
            bytes = bytes.clone();
        }

        /**
         * @param data some bytes
         * @return their SHA-256
         */
        public static Digest of(byte[] data) {
            try {
                return new Digest(MessageDigest.getInstance("SHA-256").digest(data));
            } catch (NoSuchAlgorithmException e) {
                throw new IllegalStateException("this JDK has no SHA-256", e);
            }
        }

        /**
         * @param hex 64 hex digits
         * @return the digest
         */
        public static Digest ofHex(String hex) {
            return new Digest(HexFormat.of().parseHex(hex));
        }

        /** @return the digest in hex */
        public String hex() {
            return HexFormat.of().formatHex(bytes);
        }

        @Override
        public byte[] bytes() {
            return bytes.clone();
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Digest d && MessageDigest.isEqual(d.bytes, bytes);
        }

        @Override
        public int hashCode() {
            return java.util.Arrays.hashCode(bytes);
        }

        @Override
        public String toString() {
            return "sha256:" + hex().substring(0, 12);
        }
    }
}
