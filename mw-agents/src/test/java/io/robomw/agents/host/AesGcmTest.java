package io.robomw.agents.host;

import io.robomw.agents.host.security.AesGcm;
import io.robomw.agents.host.security.FrameTag;
import io.robomw.agents.host.wire.WireFrames;
import org.junit.jupiter.api.Test;

import javax.crypto.Cipher;
import javax.crypto.spec.GCMParameterSpec;
import javax.crypto.spec.SecretKeySpec;
import java.util.Arrays;
import java.util.Locale;
import java.util.Random;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The hosts' AES-GCM provider ({@link AesGcm}): the Amazon Corretto Crypto Provider where it ships
 * (Linux on x86-64 and ARM), tags equal to the JDK's whatever the pieces, so hosts with either
 * provider talk to each other, and the refusal of a second tag under one key and nonce kept.
 */
class AesGcmTest {

    private static final SecretKeySpec KEY = new SecretKeySpec(randomBytes(32, 3), "AES");

    private static byte[] randomBytes(int n, long seed) {
        byte[] b = new byte[n];
        new Random(seed).nextBytes(b);
        return b;
    }

    @Test
    void theCorrettoProviderIsUsedOnLinuxOnX86AndArm() {
        String os = System.getProperty("os.name").toLowerCase(Locale.ROOT);
        String arch = System.getProperty("os.arch");
        boolean ships = os.contains("linux") && (arch.equals("amd64") || arch.equals("x86_64") || arch.equals("aarch64"));
        String name = AesGcm.providerName();
        if (ships && !"jdk".equals(System.getProperty(AesGcm.PROPERTY))) {
            assertTrue(name.startsWith("AmazonCorrettoCryptoProvider"), "on " + os + " " + arch + " the hosts' AES-GCM comes from " + name);
        } else {
            assertTrue(name.startsWith("JDK"), name);
        }
    }

    @Test
    void aFramesTagIsTheJdksAesGcmTagOverTheSameBytesWhateverTheLengthAndPieces() throws Exception {
        Random random = new Random(7);
        for (int length : new int[] {0, 1, 15, 16, 17, 40, 600, FrameTag.CHUNK - 1, FrameTag.CHUNK, FrameTag.CHUNK + 1, 100_003, (1 << 20) + 5}) {
            byte[] frame = new byte[length];
            random.nextBytes(frame);
            long seq = 1000 + length;
            FrameTag tag = new FrameTag();
            tag.start(KEY, WireFrames.DIRECTION_REQUEST, seq, false);
            // in uneven pieces, as reads deliver them
            for (int at = 0; at < length; ) {
                int n = Math.min(length - at, 1 + random.nextInt(70_000));
                tag.update(frame, at, n);
                at += n;
            }
            byte[] mine = tag.finish().clone();
            assertArrayEquals(jdkTag(WireFrames.DIRECTION_REQUEST, seq, frame), mine, "the tag of a frame of " + length + " bytes");

            FrameTag checking = new FrameTag();
            checking.start(KEY, WireFrames.DIRECTION_REQUEST, seq, true);
            checking.update(frame, 0, length);
            byte[] withTag = Arrays.copyOf(frame, length + WireFrames.TAG);
            System.arraycopy(mine, 0, withTag, length, WireFrames.TAG);
            assertTrue(checking.check(withTag, length), "a frame of " + length + " bytes checks");
        }
    }

    @Test
    void aSecondFrameTaggedWithTheSameNumberIsAnErrorButACheckMayRepeatOne() {
        FrameTag tag = new FrameTag();
        tag.start(KEY, WireFrames.DIRECTION_REPLY, 42, false);
        tag.update(new byte[100], 0, 100);
        tag.finish();
        IllegalStateException e = assertThrows(IllegalStateException.class, () -> tag.start(KEY, WireFrames.DIRECTION_REPLY, 42, false));
        assertTrue(e.getMessage().contains("second frame with number 42"), e.getMessage());

        // A forged copy checked first must not get the real frame refused.
        byte[] real = new byte[5000];
        new Random(1).nextBytes(real);
        byte[] realTag = tagOf(real, 43);
        FrameTag checking = new FrameTag();
        checking.start(KEY, WireFrames.DIRECTION_REPLY, 43, true);
        byte[] forged = real.clone();
        forged[10] ^= 1;
        checking.update(forged, 0, forged.length);
        assertFalse(checking.check(realTag, 0), "the forged copy fails");
        checking.start(KEY, WireFrames.DIRECTION_REPLY, 43, true);
        checking.update(real, 0, real.length);
        assertTrue(checking.check(realTag, 0), "the real frame, checked next under the same number, passes");
    }

    private static byte[] tagOf(byte[] frame, long seq) {
        FrameTag t = new FrameTag();
        t.start(KEY, WireFrames.DIRECTION_REPLY, seq, false);
        t.update(frame, 0, frame.length);
        return t.finish().clone();
    }

    private static byte[] jdkTag(int direction, long seq, byte[] frame) throws Exception {
        byte[] nonce = new byte[12];
        nonce[3] = (byte) direction;
        for (int i = 0; i < 8; i++) {
            nonce[4 + i] = (byte) (seq >>> (56 - 8 * i));
        }
        Cipher jdk = Cipher.getInstance("AES/GCM/NoPadding", "SunJCE");
        jdk.init(Cipher.ENCRYPT_MODE, KEY, new GCMParameterSpec(128, nonce));
        byte[] sealed = jdk.doFinal(frame);
        return Arrays.copyOfRange(sealed, sealed.length - WireFrames.TAG, sealed.length);
    }
}
