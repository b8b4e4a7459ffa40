package io.robomw.it.messaging;

import io.robomw.agents.messaging.TestKeys;

import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.TestInstance;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Mutual TLS over TCP and RMI between JVMs, with key stores made by keytool at test time: a peer
 * with a trusted key gets its reply; a peer with an untrusted key gets nothing through. The RMI
 * clients are given their keys also as {@code javax.net.ssl.*} properties, because RMI's client
 * sockets use the JVM's default TLS context.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
class TlsMessagingIT {

    private final List<PeerProcess> peers = new ArrayList<>();
    private PeerProcess server;
    private PeerProcess trusted;
    private PeerProcess stranger;
    private String tcp;
    private String rmi;

    @BeforeAll
    void start() throws Exception {
        java.nio.file.Files.createDirectories(Path.of("target"));
        TestKeys keys = TestKeys.create(java.nio.file.Files.createTempDirectory(Path.of("target"), "tls-keys-"));
        server = start("tls-server", keys, "node.p12");
        tcp = server.ask("bind tcp://127.0.0.1:0", "BOUND").substring(6);
        rmi = server.ask("bind rmi://127.0.0.1:0/tls-server", "BOUND").substring(6);
        server.ask("echo echo -", "OK");
        trusted = start("tls-trusted", keys, "node.p12");
        stranger = start("tls-stranger", keys, "stranger.p12");
    }

    private PeerProcess start(String name, TestKeys keys, String keyStore) throws Exception {
        String ks = keys.dir().resolve(keyStore).toString();
        String ts = keys.dir().resolve("trust.p12").toString();
        PeerProcess p = PeerProcess.peer(name, List.of("-Djavax.net.ssl.keyStore=" + ks, "-Djavax.net.ssl.keyStorePassword=" + TestKeys.PASSWORD,
                        "-Djavax.net.ssl.keyStoreType=PKCS12", "-Djavax.net.ssl.trustStore=" + ts, "-Djavax.net.ssl.trustStorePassword=" + TestKeys.PASSWORD,
                        "-Djavax.net.ssl.trustStoreType=PKCS12"),
                "--tls", ks, ts, TestKeys.PASSWORD);
        peers.add(p);
        return p;
    }

    @AfterAll
    void stop() {
        peers.forEach(PeerProcess::close);
    }

    private String host(String scheme) {
        return scheme.equals("tcp") ? tcp : rmi;
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void peerWithATrustedKeyGetsItsReply(String scheme) {
        assertEquals("REPLY hello", trusted.ask("request " + host(scheme) + " tls-server echo hello -", "REPLY", PeerProcess.COMMAND));
    }

    @ParameterizedTest
    @ValueSource(strings = {"tcp", "rmi"})
    void peerWithAnUntrustedKeyIsTurnedAway(String scheme) {
        String answer = stranger.ask("request " + host(scheme) + " tls-server echo let-me-in -", "", PeerProcess.COMMAND);
        assertTrue(answer.startsWith("FAILED") || answer.startsWith("ERR"), answer);
    }
}
