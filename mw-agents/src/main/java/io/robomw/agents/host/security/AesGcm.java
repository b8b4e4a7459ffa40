package io.robomw.agents.host.security;

import com.amazon.corretto.crypto.provider.AmazonCorrettoCryptoProvider;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import javax.crypto.Cipher;
import javax.crypto.spec.GCMParameterSpec;
import javax.crypto.spec.SecretKeySpec;
import java.security.GeneralSecurityException;
import java.security.Provider;
import java.util.Arrays;

/**
 * Where the hosts' AES-256-GCM ciphers come from ({@link FrameTag}, {@link CallAuthenticator.AesGcmTag}):
 * the Amazon Corretto Crypto Provider (ACCP, AWS-LC's AES-GCM through JNI) when it loads on this
 * machine, else the JDK's own provider. Both compute the same standard AES-GCM (NIST SP 800-38D),
 * so hosts of either kind talk to each other; ACCP only computes it faster: on the project's
 * machine a tag over 1 MiB takes about 100-120 µs with ACCP against 220 µs with JDK 17's provider
 * (JDK 25's, which uses VAES, is about as fast as ACCP; docs/benchmarks.md). ACCP, like the JDK,
 * refuses to encrypt twice with one key and nonce, which the callers rely on.
 *
 * <p>The choice is made once, when the class is first used: ACCP is taken only if its native
 * library loaded (ACCP ships it for Linux on x86-64 in the jar this module depends on) and its tag
 * of a fixed message equals the JDK's; otherwise the JDK's provider, with the reason logged. The
 * system property {@value #PROPERTY}{@code =jdk} forces the JDK's provider (for comparison, or for
 * users who want no native code).
 */
public final class AesGcm {

    /** The system property naming the provider: {@code auto} (the default: ACCP when it loads) or {@code jdk}. */
    public static final String PROPERTY = "robomw.agents.aesGcm";
    /** The transformation every cipher of the hosts uses. */
    static final String TRANSFORMATION = "AES/GCM/NoPadding";

    private static final Logger log = LoggerFactory.getLogger(AesGcm.class);
    /** The provider chosen at class initialisation, {@code null} for the JDK's (the platform's default). */
    private static final Provider PROVIDER = choose(System.getProperty(PROPERTY, "auto"));

    private AesGcm() {
    }

    /** @return a new AES/GCM/NoPadding cipher of the chosen provider */
    static Cipher newCipher() {
        if (PROVIDER == null) {
            return jdkCipher();
        }
        try {
            return Cipher.getInstance(TRANSFORMATION, PROVIDER);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException(PROVIDER.getName() + " has no " + TRANSFORMATION, e);
        }
    }

    /** @return the name of the provider the ciphers come from, for logs and benchmark reports */
    public static String providerName() {
        return PROVIDER == null ? "JDK (" + jdkCipher().getProvider().getName() + ")" : PROVIDER.getName() + " " + PROVIDER.getVersionStr();
    }

    private static Provider choose(String wanted) {
        if ("jdk".equalsIgnoreCase(wanted.trim())) {
            log.info("AES-GCM from the JDK's provider ({}=jdk)", PROPERTY);
            return null;
        }
        if (!"auto".equalsIgnoreCase(wanted.trim())) {
            log.warn("{}={} is neither auto nor jdk: taking auto", PROPERTY, wanted);
        }
        try {
            AmazonCorrettoCryptoProvider accp = AmazonCorrettoCryptoProvider.INSTANCE;
            Throwable error = accp.getLoadingError();
            if (error != null) {
                log.info("AES-GCM from the JDK's provider: the Amazon Corretto Crypto Provider did not load here ({})", error.toString());
                return null;
            }
            if (!sameTag(Cipher.getInstance(TRANSFORMATION, accp), jdkCipher())) {
                log.error("AES-GCM from the JDK's provider: the Amazon Corretto Crypto Provider's tag of a test message differs from the JDK's");
                return null;
            }
            log.info("AES-GCM from {} {} (AWS-LC)", accp.getName(), accp.getVersionStr());
            return accp;
        } catch (GeneralSecurityException | RuntimeException | LinkageError e) {
            log.info("AES-GCM from the JDK's provider: the Amazon Corretto Crypto Provider cannot be used here ({})", e.toString());
            return null;
        }
    }

    private static Cipher jdkCipher() {
        try {
            return Cipher.getInstance(TRANSFORMATION);
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this JDK has no " + TRANSFORMATION, e);
        }
    }

    /** @return whether both ciphers give the same ciphertext and tag for a fixed key, nonce and message of several pieces */
    private static boolean sameTag(Cipher a, Cipher b) throws GeneralSecurityException {
        byte[] key = new byte[32];
        byte[] nonce = new byte[12];
        byte[] message = new byte[40_000];
        for (int i = 0; i < key.length; i++) {
            key[i] = (byte) (i * 7 + 1);
        }
        for (int i = 0; i < nonce.length; i++) {
            nonce[i] = (byte) (255 - i);
        }
        for (int i = 0; i < message.length; i++) {
            message[i] = (byte) (i * 31 + (i >>> 8));
        }
        return Arrays.equals(seal(a, key, nonce, message), seal(b, key, nonce, message));
    }

    private static byte[] seal(Cipher c, byte[] key, byte[] nonce, byte[] message) throws GeneralSecurityException {
        c.init(Cipher.ENCRYPT_MODE, new SecretKeySpec(key, "AES"), new GCMParameterSpec(128, nonce));
        byte[] out = new byte[message.length + 16];
        int n = c.update(message, 0, 1000, out, 0);
        n += c.update(message, 1000, 16_384, out, n);
        n += c.doFinal(message, 17_384, message.length - 17_384, out, n);
        return Arrays.copyOf(out, n);
    }
}
