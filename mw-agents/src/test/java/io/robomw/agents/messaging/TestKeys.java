package io.robomw.agents.messaging;

import io.robomw.agents.messaging.security.TlsSettings;

import java.io.IOException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * Test-only key stores made at test time with the JDK's {@code keytool}: a "node" key trusted by
 * the trust store, and a "stranger" key that is not. No key material is committed.
 */
public final class TestKeys {

    /** The password of every store made here. */
    public static final String PASSWORD = "test-only-password";

    private final Path dir;

    private TestKeys(Path dir) {
        this.dir = dir;
    }

    /**
     * @param dir an empty directory
     * @return the keys, made there
     * @throws IOException if keytool fails
     */
    public static TestKeys create(Path dir) throws IOException, InterruptedException {
        TestKeys k = new TestKeys(dir);
        k.keytool("-genkeypair", "-alias", "node", "-keyalg", "EC", "-groupname", "secp256r1", "-dname", "CN=robomw-test-node",
                "-validity", "2", "-keystore", dir.resolve("node.p12").toString(), "-storetype", "PKCS12", "-storepass", PASSWORD, "-keypass", PASSWORD);
        k.keytool("-genkeypair", "-alias", "stranger", "-keyalg", "EC", "-groupname", "secp256r1", "-dname", "CN=robomw-test-stranger",
                "-validity", "2", "-keystore", dir.resolve("stranger.p12").toString(), "-storetype", "PKCS12", "-storepass", PASSWORD, "-keypass", PASSWORD);
        k.keytool("-exportcert", "-alias", "node", "-keystore", dir.resolve("node.p12").toString(), "-storepass", PASSWORD,
                "-file", dir.resolve("node.cer").toString());
        k.keytool("-importcert", "-noprompt", "-alias", "node", "-file", dir.resolve("node.cer").toString(),
                "-keystore", dir.resolve("trust.p12").toString(), "-storetype", "PKCS12", "-storepass", PASSWORD);
        return k;
    }

    /** @return TLS with the trusted node key */
    public TlsSettings node() {
        return new TlsSettings(dir.resolve("node.p12"), PASSWORD, dir.resolve("trust.p12"), PASSWORD);
    }

    /** @return TLS with a key the trust store does not vouch for */
    public TlsSettings stranger() {
        return new TlsSettings(dir.resolve("stranger.p12"), PASSWORD, dir.resolve("trust.p12"), PASSWORD);
    }

    private void keytool(String... args) throws IOException, InterruptedException {
        List<String> command = new ArrayList<>();
        command.add(Path.of(System.getProperty("java.home"), "bin", "keytool").toString());
        command.addAll(List.of(args));
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        try {
            String out = new String(p.getInputStream().readAllBytes());
            if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
                throw new IOException("keytool " + String.join(" ", args) + " failed: " + out);
            }
        } finally {
            p.destroyForcibly();
        }
    }

    /** @return the directory holding the stores */
    public Path dir() {
        return dir;
    }
}
