package io.robomw.agents.host;

import javax.crypto.AEADBadTagException;
import javax.crypto.Cipher;
import javax.crypto.Mac;
import javax.crypto.spec.GCMParameterSpec;
import javax.crypto.spec.SecretKeySpec;
import java.security.GeneralSecurityException;
import java.security.InvalidAlgorithmParameterException;

/**
 * What proves that a call between hosts, and its reply, come from the holder of the session key
 * and were not changed on the way: a {@value #TAG}-byte tag over the whole message, under the
 * session key ({@link Session}). A peer names the authenticator it uses in its authentication
 * request, by code; a host refuses a code it does not know, naming it.
 *
 * <table>
 * <caption>Authenticator codes</caption>
 * <tr><th>code</th><th>authenticator</th><th>request tag</th><th>reply tag</th></tr>
 * <tr><td>1</td><td>HMAC-SHA256-128 (the protocol-1 MAC, RFC 4868's truncation)</td>
 *     <td>HMAC(len ‖ request)</td><td>HMAC(len ‖ "reply" ‖ len ‖ seq ‖ len ‖ reply), each len a u32</td></tr>
 * <tr><td>2</td><td>AES-256-GMAC: AES-256-GCM (NIST SP 800-38D) with the message as additional
 *     authenticated data and no plaintext; what hosts of this build propose</td>
 *     <td>nonce [0 0 0 0][seq 8]</td><td>nonce [0 0 0 1][seq 8]</td></tr>
 * </table>
 *
 * <p><b>Why AES-GMAC.</b> The JDK runs AES-GCM on the processor's AES and carry-less multiply
 * instructions (AES-NI, PCLMULQDQ; with AVX-512, VAES and VPCLMULQDQ), several times faster than
 * HMAC-SHA256 over large messages on the project's machine (docs/benchmarks.md, ceilings), and an
 * agent's state is MAC'd twice per hop (seal and check). GMAC's one demand is a nonce never used
 * twice under one key: each session has a key of its own (from both sides' fresh nonces), a
 * request's nonce is its sequence number, which the peer never repeats on a session, and a reply's
 * is the request's number in the other half of the nonce space; the host answers a number at most
 * once (its session's replay window refuses the second), and the JDK's own refusal to encrypt
 * twice with one key and nonce is turned into an error rather than a tag.
 *
 * <p>Thread-safe: each thread gets its own initialised {@link Mac} or {@link Cipher}.
 */
abstract sealed class CallAuthenticator permits CallAuthenticator.HmacSha256, CallAuthenticator.AesGmac {

    /** Length of a tag, bytes. */
    static final int TAG = 16;
    /** Code of HMAC-SHA256-128. */
    static final int HMAC_SHA256_128 = 1;
    /** Code of AES-256-GMAC. */
    static final int AES_256_GMAC = 2;
    /** The authenticator peers of this build propose. */
    static final int DEFAULT = AES_256_GMAC;

    /**
     * @param code       an authenticator code
     * @param sessionKey the session's 32-byte key
     * @return the authenticator
     * @throws IllegalArgumentException naming the code if it is not in the table
     */
    static CallAuthenticator of(int code, byte[] sessionKey) {
        return switch (code) {
            case HMAC_SHA256_128 -> new HmacSha256(sessionKey);
            case AES_256_GMAC -> new AesGmac(sessionKey);
            default -> throw new IllegalArgumentException(unknown(code));
        };
    }

    /** @return whether a code is in the table */
    static boolean known(int code) {
        return code == HMAC_SHA256_128 || code == AES_256_GMAC;
    }

    /** @return the error text for a code not in the table */
    static String unknown(int code) {
        return "unknown call authenticator code " + code + " (known: " + HMAC_SHA256_128 + " HMAC-SHA256-128, " + AES_256_GMAC + " AES-256-GMAC)";
    }

    /** @return this authenticator's code */
    abstract int code();

    /**
     * Writes the tag of a message into {@code out}.
     *
     * @param reply  whether the message is a reply (else a request)
     * @param seq    the request's sequence number (a reply's: the request's it answers)
     * @param data   holds the message
     * @param off    where it starts
     * @param len    its length
     * @param out    where the tag goes
     * @param outOff where in {@code out}
     */
    abstract void tag(boolean reply, long seq, byte[] data, int off, int len, byte[] out, int outOff);

    /**
     * @return whether the tag at {@code tagOff} in {@code tag} is the message's (compared in constant time)
     */
    abstract boolean verify(boolean reply, long seq, byte[] data, int off, int len, byte[] tag, int tagOff);

    /** Code 1: today's HMAC-SHA256, truncated to 128 bits. */
    static final class HmacSha256 extends CallAuthenticator {
        private static final byte[] REPLY = "reply".getBytes(java.nio.charset.StandardCharsets.US_ASCII);
        private final SecretKeySpec key;
        private final ThreadLocal<Mac> macs;

        HmacSha256(byte[] sessionKey) {
            this.key = new SecretKeySpec(sessionKey, "HmacSHA256");
            this.macs = ThreadLocal.withInitial(this::newMac);
        }

        private Mac newMac() {
            try {
                Mac m = Mac.getInstance("HmacSHA256");
                m.init(key);
                return m;
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("this JDK has no HmacSHA256", e);
            }
        }

        @Override
        int code() {
            return HMAC_SHA256_128;
        }

        private byte[] mac(boolean reply, long seq, byte[] data, int off, int len) {
            // As ClusterKey.hmac would compute it over the parts (each prefixed with its length), in place.
            Mac m = macs.get();
            if (reply) {
                updateLength(m, REPLY.length);
                m.update(REPLY);
                updateLength(m, 8);
                for (int shift = 56; shift >= 0; shift -= 8) {
                    m.update((byte) (seq >>> shift));
                }
            }
            updateLength(m, len);
            m.update(data, off, len);
            return m.doFinal();
        }

        private static void updateLength(Mac m, int n) {
            m.update((byte) (n >>> 24));
            m.update((byte) (n >>> 16));
            m.update((byte) (n >>> 8));
            m.update((byte) n);
        }

        @Override
        void tag(boolean reply, long seq, byte[] data, int off, int len, byte[] out, int outOff) {
            System.arraycopy(mac(reply, seq, data, off, len), 0, out, outOff, TAG);
        }

        @Override
        boolean verify(boolean reply, long seq, byte[] data, int off, int len, byte[] tag, int tagOff) {
            byte[] m = mac(reply, seq, data, off, len);
            int diff = 0;
            for (int i = 0; i < TAG; i++) {
                diff |= m[i] ^ tag[tagOff + i];
            }
            return diff == 0;
        }
    }

    /** Code 2: AES-256-GCM over no plaintext, the message being the additional authenticated data. */
    static final class AesGmac extends CallAuthenticator {
        private final SecretKeySpec key;
        /** Per thread: [0] tags (encryption mode), [1] checks (decryption mode, which tells a wrong tag by an exception). */
        private final ThreadLocal<Cipher[]> ciphers = ThreadLocal.withInitial(AesGmac::newCiphers);

        AesGmac(byte[] sessionKey) {
            if (sessionKey.length != 32) {
                throw new IllegalArgumentException("AES-256-GMAC needs a 32-byte key, got " + sessionKey.length);
            }
            this.key = new SecretKeySpec(sessionKey, "AES");
        }

        private static Cipher[] newCiphers() {
            try {
                return new Cipher[] {Cipher.getInstance("AES/GCM/NoPadding"), Cipher.getInstance("AES/GCM/NoPadding")};
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("this JDK has no AES/GCM/NoPadding", e);
            }
        }

        @Override
        int code() {
            return AES_256_GMAC;
        }

        /** [0 0 0 direction][seq, big-endian]: requests and replies never share a nonce. */
        private static GCMParameterSpec nonce(boolean reply, long seq) {
            byte[] n = new byte[12];
            n[3] = (byte) (reply ? 1 : 0);
            for (int i = 0; i < 8; i++) {
                n[4 + i] = (byte) (seq >>> (56 - 8 * i));
            }
            return new GCMParameterSpec(TAG * 8, n);
        }

        @Override
        void tag(boolean reply, long seq, byte[] data, int off, int len, byte[] out, int outOff) {
            Cipher c = ciphers.get()[0];
            try {
                c.init(Cipher.ENCRYPT_MODE, key, nonce(reply, seq));
            } catch (InvalidAlgorithmParameterException e) {
                // The JDK refuses a key and nonce it has just used: a number tagged twice is a bug here, never sent.
                throw new IllegalStateException("refusing to tag a second message with " + (reply ? "reply" : "request") + " number " + seq
                        + " under one session key: " + e.getMessage(), e);
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("AES-GCM refused the session key: " + e, e);
            }
            try {
                c.updateAAD(data, off, len);
                int n = c.doFinal(out, outOff);
                if (n != TAG) {
                    throw new IllegalStateException("AES-GCM made a tag of " + n + " bytes, expected " + TAG);
                }
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("AES-GCM failed to tag a message: " + e, e);
            }
        }

        @Override
        boolean verify(boolean reply, long seq, byte[] data, int off, int len, byte[] tag, int tagOff) {
            Cipher c = ciphers.get()[1];
            try {
                c.init(Cipher.DECRYPT_MODE, key, nonce(reply, seq));
                c.updateAAD(data, off, len);
                c.doFinal(tag, tagOff, TAG); // compares the tags in constant time
                return true;
            } catch (AEADBadTagException e) {
                return false;
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("AES-GCM failed to check a message: " + e, e);
            }
        }
    }
}
