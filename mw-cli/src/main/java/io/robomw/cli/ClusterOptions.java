package io.robomw.cli;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.ClusterKeyLookup;
import io.robomw.agents.messaging.security.TlsSettings;
import io.robomw.api.spi.AgencyConfig;
import io.robomw.api.spi.SecretRef;
import picocli.CommandLine.Option;

import java.io.IOException;
import java.nio.file.Path;
import java.util.Optional;

/** How an agent command proves it belongs to the cluster: the cluster key, and optionally mutual TLS. */
final class ClusterOptions {

    /** Environment variable holding the cluster passphrase when no key file is given. */
    static final String KEY_VARIABLE = AgencyConfig.KEY_VARIABLE;

    @Option(names = "--key-file", paramLabel = "FILE", description = "file holding the cluster passphrase (default: the " + KEY_VARIABLE
            + " environment variable, then ~/" + AgencyConfig.DEFAULT_KEY_FILE + ")")
    Path keyFile;

    @Option(names = "--tls-keystore", paramLabel = "FILE", description = "PKCS#12 key store: turns on mutual TLS for the RMI endpoint")
    Path keyStore;

    @Option(names = "--tls-truststore", paramLabel = "FILE", description = "PKCS#12 store of the peers to trust (default: the key store)")
    Path trustStore;

    @Option(names = "--tls-password-file", paramLabel = "FILE", description = "file holding the password of both stores (default: the "
            + Secrets.TLS_PASSWORD_ENV + " environment variable, else none)")
    Path storePasswordFile;

    /** Refused: a secret on the command line shows in ps. */
    @Option(names = "--tls-password", hidden = true, converter = Secrets.RefusedTlsPassword.class)
    String refusedStorePassword;

    ClusterKey key() throws IOException {
        ClusterKeyLookup lookup = ClusterKeyLookup.ofThisProcess();
        Optional<SecretRef> file = Optional.ofNullable(keyFile).map(f -> new SecretRef(SecretRef.Kind.FILE, f.toString(), "--key-file"));
        Optional<ClusterKey> key = lookup.find(file);
        if (key.isPresent() || keyStore != null) {
            return key.orElse(null); // without a key, TLS alone authenticates
        }
        return lookup.require(file, "this command");
    }

    /**
     * The key when the command can authenticate, for commands that do more with it but need none
     * ({@code mw agents --cluster}): a key file given must exist, one looked up may be absent.
     *
     * @return the cluster key (or the TLS-only key when TLS alone authenticates), or empty if none is given or found
     * @throws IOException if the key file given cannot be read
     */
    Optional<ClusterKey> keyIfAny() throws IOException {
        if (keyFile != null || keyStore != null) {
            return Optional.of(keyOrTlsOnly());
        }
        return ClusterKeyLookup.ofThisProcess().find(Optional.empty());
    }

    /** @return the cluster key, or the TLS-only key when TLS alone authenticates */
    ClusterKey keyOrTlsOnly() throws IOException {
        ClusterKey k = key();
        return k == null ? ClusterKey.tlsOnly() : k;
    }

    TlsSettings tls() {
        if (keyStore == null) {
            return null;
        }
        // The client side of RMI uses the JVM's default TLS context: point it at the same stores.
        Path trust = trustStore == null ? keyStore : trustStore;
        String storePassword = Secrets.read(storePasswordFile, "--tls-password-file", Secrets.TLS_PASSWORD_ENV).orElse("");
        System.setProperty("javax.net.ssl.keyStore", keyStore.toString());
        System.setProperty("javax.net.ssl.keyStorePassword", storePassword);
        System.setProperty("javax.net.ssl.trustStore", trust.toString());
        System.setProperty("javax.net.ssl.trustStorePassword", storePassword);
        return new TlsSettings(keyStore, storePassword, trust, storePassword);
    }
}
