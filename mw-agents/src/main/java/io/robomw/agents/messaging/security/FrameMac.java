package io.robomw.agents.messaging.security;

import io.robomw.agents.messaging.frame.FrameCodec;

import javax.crypto.Mac;
import javax.crypto.SecretKey;
import java.security.GeneralSecurityException;
import java.security.InvalidKeyException;
import java.security.MessageDigest;

/**
 * Signs and verifies frames with HMAC-SHA256. The MAC covers the frame's bytes except the stream
 * sequence (see {@link FrameCodec}) and sits in the last {@value FrameCodec#MAC_LENGTH} bytes.
 *
 * <p>Thread-safe: each thread uses its own {@link Mac}.
 */
public final class FrameMac {

    private final ThreadLocal<Mac> macs = ThreadLocal.withInitial(FrameMac::newMac);

    /**
     * Computes the MAC of an encoded frame (made with room for it) and writes it at the end.
     *
     * @param key   the topic key
     * @param frame the frame
     */
    public void sign(SecretKey key, byte[] frame) {
        byte[] mac = compute(key, frame, 0, frame.length);
        System.arraycopy(mac, 0, frame, frame.length - FrameCodec.MAC_LENGTH, FrameCodec.MAC_LENGTH);
    }

    /**
     * @param key    the topic key
     * @param buf    bytes holding the frame
     * @param offset where it starts
     * @param length its length, MAC included
     * @return whether the MAC at its end is right (compared in constant time)
     */
    public boolean verify(SecretKey key, byte[] buf, int offset, int length) {
        if (length < FrameCodec.HEADER_LENGTH + FrameCodec.MAC_LENGTH) {
            return false;
        }
        byte[] expected = compute(key, buf, offset, length);
        byte[] actual = new byte[FrameCodec.MAC_LENGTH];
        System.arraycopy(buf, offset + length - FrameCodec.MAC_LENGTH, actual, 0, FrameCodec.MAC_LENGTH);
        return MessageDigest.isEqual(expected, actual);
    }

    private byte[] compute(SecretKey key, byte[] buf, int offset, int length) {
        Mac mac = macs.get();
        try {
            mac.init(key);
        } catch (InvalidKeyException e) {
            throw new IllegalArgumentException("not an HMAC key: " + key.getAlgorithm(), e);
        }
        mac.update(buf, offset, FrameCodec.STREAM_SEQUENCE_OFFSET);
        int rest = FrameCodec.FLAGS_OFFSET;
        mac.update(buf, offset + rest, length - rest - FrameCodec.MAC_LENGTH);
        return mac.doFinal();
    }

    private static Mac newMac() {
        try {
            return Mac.getInstance("HmacSHA256");
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK has no HmacSHA256: " + e, e);
        }
    }
}
