package io.robomw.agents.host.security;

import io.robomw.agents.host.rmi.Session;
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
 * <tr><td>2</td><td>AES-256-GCM tag: the tag of AES-256-GCM (NIST SP 800-38D) over the message as
 *     its plaintext (the ciphertext is not sent: see {@link AesGcmTag}); what hosts of this build propose</td>
 *     <td>nonce [0 0 0 0][seq 8]</td><td>nonce [0 0 0 1][seq 8]</td></tr>
 * </table>
 *
 * <p><b>Why AES-GCM.</b> AES-GCM runs on the processor's AES and carry-less multiply
 * instructions (AES-NI, PCLMULQDQ; with AVX-512, VAES and VPCLMULQDQ; the ciphers come from
 * {@link AesGcm}: the Amazon Corretto Crypto Provider where it loads, else the JDK's), several times faster than
 * HMAC-SHA256 over large messages on the project's machine (docs/benchmarks.md, ceilings), and an
 * agent's state is MAC'd twice per hop (seal and check). GCM's one demand is a nonce never used
 * twice under one key: each session has a key of its own (from both sides' fresh nonces), a
 * request's nonce is its sequence number, which the peer never repeats on a session, and a reply's
 * is the request's number in the other half of the nonce space; the host answers a number at most
 * once (its session's replay window refuses the second), and the provider's own refusal to encrypt
 * twice with one key and nonce (the JDK's and ACCP's alike) is turned into an error rather than a tag.
 * The ciphertext is never sent, and a tag is revealed only by the side that made the message; the
 * side that checks computes it the same way and says only yes or no.
 *
 * <p>Thread-safe: each thread gets its own initialised {@link Mac} or {@link Cipher}.
 */
public abstract sealed class CallAuthenticator permits CallAuthenticator.HmacSha256, CallAuthenticator.AesGcmTag {

    /** Length of a tag, bytes. */
    public static final int TAG = 16;
    /** Code of HMAC-SHA256-128. */
    public static final int HMAC_SHA256_128 = 1;
    /** Code of AES-256-GCM tag. */
    public static final int AES_256_GCM = 2;
    /** The authenticator peers of this build propose. */
    public static final int DEFAULT = AES_256_GCM;

    /**
     * @param code       an authenticator code
     * @param sessionKey the session's 32-byte key
     * @return the authenticator
     * @throws IllegalArgumentException naming the code if it is not in the table
     */
    public static CallAuthenticator of(int code, byte[] sessionKey) {
        return switch (code) {
            case HMAC_SHA256_128 -> new HmacSha256(sessionKey);
            case AES_256_GCM -> new AesGcmTag(sessionKey);
            default -> throw new IllegalArgumentException(unknown(code));
        };
    }

    /** @return whether a code is in the table */
    public static boolean known(int code) {
        return code == HMAC_SHA256_128 || code == AES_256_GCM;
    }

    /** @return the error text for a code not in the table */
    public static String unknown(int code) {
        return "unknown call authenticator code " + code + " (known: " + HMAC_SHA256_128 + " HMAC-SHA256-128, " + AES_256_GCM + " AES-256-GCM tag)";
    }

    /** @return this authenticator's code */
    public abstract int code();

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
    public abstract void tag(boolean reply, long seq, byte[] data, int off, int len, byte[] out, int outOff);

    /**
     * @return whether the tag at {@code tagOff} in {@code tag} is the message's (compared in constant time)
     */
    public abstract boolean verify(boolean reply, long seq, byte[] data, int off, int len, byte[] tag, int tagOff);

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
        public int code() {
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
        public void tag(boolean reply, long seq, byte[] data, int off, int len, byte[] out, int outOff) {
            System.arraycopy(mac(reply, seq, data, off, len), 0, out, outOff, TAG);
        }

        @Override
        public boolean verify(boolean reply, long seq, byte[] data, int off, int len, byte[] tag, int tagOff) {
            byte[] m = mac(reply, seq, data, off, len);
            int diff = 0;
            for (int i = 0; i < TAG; i++) {
                diff |= m[i] ^ tag[tagOff + i];
            }
            return diff == 0;
        }
    }

    /**
     * Code 2: AES-256-GCM's tag over the message. The message is run through AES-256-GCM
     * encryption as its plaintext, in chunks into a small buffer of this thread whose ciphertext
     * nobody reads, and the tag is GCM's, as strong as GMAC (a forger must forge a GCM
     * tag: a changed message is a changed ciphertext), without the JDK's copies of additional
     * authenticated data (JDK 17 buffers AAD in full, twice: a 1 MB call cost as much as
     * HMAC-SHA256), and on the AES-CTR and GHASH intrinsics, which process the chunks as they
     * come. Checking computes the tag the same way and compares it in constant time.
     */
    static final class AesGcmTag extends CallAuthenticator {
        /** Chunk the message goes through GCM in: a multiple of the block, small enough to stay in the cache. */
        private static final int CHUNK = 16 * 1024;
        private final SecretKeySpec key;
        /** Per thread: [0] for tags it sends, [1] for tags it checks (the provider refuses one cipher the nonce it has just used). */
        private final ThreadLocal<Cipher[]> ciphers = ThreadLocal.withInitial(AesGcmTag::newCiphers);
        private final ThreadLocal<byte[]> scratch = ThreadLocal.withInitial(() -> new byte[CHUNK + TAG]);

        AesGcmTag(byte[] sessionKey) {
            if (sessionKey.length != 32) {
                throw new IllegalArgumentException("AES-256-GCM tag needs a 32-byte key, got " + sessionKey.length);
            }
            this.key = new SecretKeySpec(sessionKey, "AES");
        }

        private static Cipher[] newCiphers() {
            return new Cipher[] {AesGcm.newCipher(), AesGcm.newCipher()};
        }

        @Override
        public int code() {
            return AES_256_GCM;
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

        /** A nonce no tag uses (a tag's begins with three zero bytes): to make a checking cipher forget the last one. */
        private static final GCMParameterSpec FORGET = new GCMParameterSpec(TAG * 8, new byte[] {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1});

        /**
         * Runs the message through GCM and leaves its tag in the scratch buffer.
         *
         * @param checking whether the tag is to be checked (never sent) rather than sent
         * @return where the tag starts in the scratch buffer
         */
        private int gcm(Cipher c, boolean checking, boolean reply, long seq, byte[] data, int off, int len) throws GeneralSecurityException {
            try {
                c.init(Cipher.ENCRYPT_MODE, key, nonce(reply, seq));
            } catch (InvalidAlgorithmParameterException e) {
                if (!checking) {
                    throw e;
                }
                // The provider refuses a cipher the key and nonce it has just used. A check sends nothing, and a
                // tampered copy of a call checked just before the call must not get the call refused: make
                // the cipher forget, and check.
                c.init(Cipher.ENCRYPT_MODE, key, FORGET);
                c.init(Cipher.ENCRYPT_MODE, key, nonce(reply, seq));
            }
            byte[] out = scratch.get();
            int at = off;
            int end = off + len;
            while (end - at > CHUNK) {
                c.update(data, at, CHUNK, out, 0);
                at += CHUNK;
            }
            return c.doFinal(data, at, end - at, out, 0) - TAG;
        }

        @Override
        public void tag(boolean reply, long seq, byte[] data, int off, int len, byte[] out, int outOff) {
            try {
                int t = gcm(ciphers.get()[0], false, reply, seq, data, off, len);
                System.arraycopy(scratch.get(), t, out, outOff, TAG);
            } catch (InvalidAlgorithmParameterException e) {
                // The provider refuses a key and nonce it has just used: a number tagged twice is a bug here, never sent.
                throw new IllegalStateException("refusing to tag a second message with " + (reply ? "reply" : "request") + " number " + seq
                        + " under one session key: " + e.getMessage(), e);
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("AES-GCM failed to tag a message: " + e, e);
            }
        }

        @Override
        public boolean verify(boolean reply, long seq, byte[] data, int off, int len, byte[] tag, int tagOff) {
            int t;
            try {
                t = gcm(ciphers.get()[1], true, reply, seq, data, off, len);
            } catch (GeneralSecurityException e) {
                throw new IllegalStateException("AES-GCM failed to check a message: " + e, e);
            }
            byte[] mine = scratch.get();
            int diff = 0;
            for (int i = 0; i < TAG; i++) {
                diff |= mine[t + i] ^ tag[tagOff + i];
            }
            return diff == 0;
        }
    }
}
