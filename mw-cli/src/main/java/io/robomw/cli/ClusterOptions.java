package io.robomw.cli;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.messaging.security.TlsSettings;
import picocli.CommandLine.Option;

import java.io.IOException;
import java.nio.file.Path;

/** How an agent command proves it belongs to the cluster: the cluster key, and optionally mutual TLS. */
final class ClusterOptions {

    /** Environment variable holding the cluster passphrase when no key file is given. */
    static final String KEY_VARIABLE = "MW_CLUSTER_KEY";

    @Option(names = "--key-file", paramLabel = "FILE", description = "file holding the cluster passphrase (default: the " + KEY_VARIABLE + " environment variable)")
    Path keyFile;

    @Option(names = "--tls-keystore", paramLabel = "FILE", description = "PKCS#12 key store: turns on mutual TLS for the RMI endpoint")
    Path keyStore;

    @Option(names = "--tls-truststore", paramLabel = "FILE", description = "PKCS#12 store of the peers to trust (default: the key store)")
    Path trustStore;

    @Option(names = "--tls-password", description = "password of both stores", defaultValue = "")
    String storePassword;

    ClusterKey key() throws IOException {
        if (keyFile != null) {
            return ClusterKey.read(keyFile);
        }
        String env = System.getenv(KEY_VARIABLE);
        if (env != null && !env.isBlank()) {
            return ClusterKey.fromPassphrase(env.strip());
        }
        if (keyStore != null) {
            return null; // TLS alone authenticates
        }
        throw new IOException("no cluster key: give --key-file FILE or set " + KEY_VARIABLE + " (every host of a cluster must share it)");
    }

    TlsSettings tls() {
        if (keyStore == null) {
            return null;
        }
        // The client side of RMI uses the JVM's default TLS context: point it at the same stores.
        Path trust = trustStore == null ? keyStore : trustStore;
        System.setProperty("javax.net.ssl.keyStore", keyStore.toString());
        System.setProperty("javax.net.ssl.keyStorePassword", storePassword);
        System.setProperty("javax.net.ssl.trustStore", trust.toString());
        System.setProperty("javax.net.ssl.trustStorePassword", storePassword);
        return new TlsSettings(keyStore, storePassword, trust, storePassword);
    }
}
