package io.robomw.agents.messaging.security;

import javax.net.ssl.KeyManagerFactory;
import javax.net.ssl.SSLContext;
import javax.net.ssl.TrustManagerFactory;
import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.util.Objects;

/**
 * TLS with mutual authentication for the TCP and RMI transports: this node proves who it is with
 * the key in {@code keyStore} and accepts only peers whose certificate {@code trustStore}
 * vouches for. Both sides of a connection check each other.
 *
 * @param keyStore           PKCS#12 (or JKS) file with this node's private key and certificate
 * @param keyStorePassword   its password
 * @param trustStore         file with the certificates (or their CA) of the peers to accept
 * @param trustStorePassword its password
 */
public record TlsSettings(Path keyStore, String keyStorePassword, Path trustStore, String trustStorePassword) {

    /** Checks that every part is given. */
    public TlsSettings {
        Objects.requireNonNull(keyStore, "keyStore");
        Objects.requireNonNull(keyStorePassword, "keyStorePassword");
        Objects.requireNonNull(trustStore, "trustStore");
        Objects.requireNonNull(trustStorePassword, "trustStorePassword");
    }

    /**
     * @return a TLS context with this node's key and the trusted peers
     * @throws IOException naming the file that cannot be read or the password that does not open it
     */
    public SSLContext context() throws IOException {
        try {
            KeyManagerFactory keys = KeyManagerFactory.getInstance(KeyManagerFactory.getDefaultAlgorithm());
            keys.init(load(keyStore, keyStorePassword), keyStorePassword.toCharArray());
            TrustManagerFactory trust = TrustManagerFactory.getInstance(TrustManagerFactory.getDefaultAlgorithm());
            trust.init(load(trustStore, trustStorePassword));
            SSLContext context = SSLContext.getInstance("TLS");
            context.init(keys.getKeyManagers(), trust.getTrustManagers(), null);
            return context;
        } catch (GeneralSecurityException e) {
            throw new IOException("cannot set up TLS from key store " + keyStore + " and trust store " + trustStore + ": " + e.getMessage(), e);
        }
    }

    /**
     * @return key managers with this node's key (for libraries that take the factories, such as the MQTT client)
     * @throws IOException naming the file that cannot be read or the password that does not open it
     */
    public KeyManagerFactory keyManagerFactory() throws IOException {
        try {
            KeyManagerFactory keys = KeyManagerFactory.getInstance(KeyManagerFactory.getDefaultAlgorithm());
            keys.init(load(keyStore, keyStorePassword), keyStorePassword.toCharArray());
            return keys;
        } catch (GeneralSecurityException e) {
            throw new IOException("cannot read the key in key store " + keyStore + ": " + e.getMessage(), e);
        }
    }

    /**
     * @return trust managers that accept the peers of the trust store
     * @throws IOException naming the file that cannot be read or the password that does not open it
     */
    public TrustManagerFactory trustManagerFactory() throws IOException {
        return trustManagerFactory(trustStore, trustStorePassword);
    }

    /**
     * @param file     a PKCS#12 or JKS trust store ({@code .jks} is read as JKS)
     * @param password its password
     * @return trust managers that accept what it vouches for
     * @throws IOException naming the file that cannot be read
     */
    public static TrustManagerFactory trustManagerFactory(Path file, String password) throws IOException {
        try {
            TrustManagerFactory trust = TrustManagerFactory.getInstance(TrustManagerFactory.getDefaultAlgorithm());
            trust.init(load(file, password));
            return trust;
        } catch (GeneralSecurityException e) {
            throw new IOException("cannot read the certificates in trust store " + file + ": " + e.getMessage(), e);
        }
    }

    private static KeyStore load(Path file, String password) throws IOException, GeneralSecurityException {
        String type = file.toString().endsWith(".jks") ? "JKS" : "PKCS12";
        KeyStore store = KeyStore.getInstance(type);
        try (InputStream in = Files.newInputStream(file)) {
            store.load(in, password.toCharArray());
        } catch (IOException e) {
            throw new IOException("cannot open " + type + " store " + file + " (wrong password, or not a " + type + " file): " + e.getMessage(), e);
        }
        return store;
    }
}
