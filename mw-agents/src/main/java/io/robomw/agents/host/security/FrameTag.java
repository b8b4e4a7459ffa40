package io.robomw.agents.host.security;

import io.robomw.agents.host.wire.WireFrames;
import javax.crypto.Cipher;
import javax.crypto.spec.GCMParameterSpec;
import javax.crypto.spec.SecretKeySpec;
import java.security.GeneralSecurityException;
import java.security.InvalidAlgorithmParameterException;

/**
 * The tag of one agent wire frame ({@link WireFrames}), computed piece by piece as the frame is
 * written or read: AES-256-GCM under the session key with the frame (header and body) as its
 * plaintext, whose ciphertext nobody reads, as {@link CallAuthenticator.AesGcmTag} does for a
 * whole RMI call. Fed in the pieces the frame is written or read in, each piece goes through GCM
 * while it is still in the processor's cache from the copy to or from the socket.
 *
 * <p>The nonce is {@code [0 0 0 direction][seq]}: direction {@value WireFrames#DIRECTION_REQUEST}
 * for a request (peer to host), {@value WireFrames#DIRECTION_REPLY} for its reply, so frames never
 * share a nonce with each other nor with the RMI calls of the same session (directions 0 and 1).
 *
 * <p>One per connection side; not thread-safe (a connection carries one frame at a time).
 */
public final class FrameTag {

    /**
     * The most bytes given to GCM at once: a multiple of the block, small enough to stay in the cache,
     * large enough that ACCP's call into its native code is paid rarely (a tag of 1 MiB: about 103 µs
     * in 64 KiB pieces against 121 in 16 KiB ones; the JDK's provider takes the same time either way).
     */
    public static final int CHUNK = 64 * 1024;
    /** A nonce no frame uses (a frame's begins with three zero bytes): makes a checking cipher forget its last nonce. */
    private static final GCMParameterSpec FORGET = new GCMParameterSpec(128, new byte[] {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1});

    private final Cipher cipher;
    private final byte[] scratch = new byte[CHUNK + 2 * WireFrames.TAG];
    private final byte[] tag = new byte[WireFrames.TAG];
    /** The nonce's bytes, rewritten for each frame ({@link GCMParameterSpec} copies them). */
    private final byte[] nonceBytes = new byte[12];

    public FrameTag() {
        cipher = AesGcm.newCipher();
    }

    /**
     * Starts the tag of a frame.
     *
     * @param key       the session's frame key
     * @param direction {@link WireFrames#DIRECTION_REQUEST} or {@link WireFrames#DIRECTION_REPLY}
     * @param seq       the request's sequence number
     * @param checking  whether the tag will be checked (a received frame) rather than sent
     */
    public void start(SecretKeySpec key, int direction, long seq, boolean checking) {
        byte[] n = nonceBytes;
        n[3] = (byte) direction;
        for (int i = 0; i < 8; i++) {
            n[4 + i] = (byte) (seq >>> (56 - 8 * i));
        }
        GCMParameterSpec nonce = new GCMParameterSpec(128, n);
        try {
            try {
                cipher.init(Cipher.ENCRYPT_MODE, key, nonce);
            } catch (InvalidAlgorithmParameterException e) {
                if (!checking) {
                    // The provider (the JDK's and ACCP alike) refuses the key and nonce it has just used: a number sent twice is a bug here, never sent.
                    throw new IllegalStateException("refusing to tag a second frame with number " + seq + " under one session key: " + e.getMessage(), e);
                }
                // A check sends nothing: a forged frame checked just before the real one must not get it refused.
                cipher.init(Cipher.ENCRYPT_MODE, key, FORGET);
                cipher.init(Cipher.ENCRYPT_MODE, key, nonce);
            }
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("AES-GCM cannot start a frame tag: " + e, e);
        }
    }

    /** Feeds the next piece of the frame. */
    public void update(byte[] data, int off, int len) {
        try {
            int end = off + len;
            for (int at = off; at < end; at += CHUNK) {
                cipher.update(data, at, Math.min(CHUNK, end - at), scratch, 0);
            }
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("AES-GCM failed on a frame: " + e, e);
        }
    }

    /** @return the tag of everything fed since {@link #start} (an array of this object's, overwritten by the next frame) */
    public byte[] finish() {
        try {
            int n = cipher.doFinal(scratch, 0);
            System.arraycopy(scratch, n - WireFrames.TAG, tag, 0, WireFrames.TAG);
            return tag;
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("AES-GCM failed to finish a frame tag: " + e, e);
        }
    }

    /** @return whether the tag at {@code off} in {@code received} is the one of everything fed (constant time) */
    public boolean check(byte[] received, int off) {
        byte[] mine = finish();
        int diff = 0;
        for (int i = 0; i < WireFrames.TAG; i++) {
            diff |= mine[i] ^ received[off + i];
        }
        return diff == 0;
    }
}
