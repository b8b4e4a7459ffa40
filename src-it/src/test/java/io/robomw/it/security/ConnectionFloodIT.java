package io.robomw.it.security;

import io.robomw.agents.host.AgentHostRemote;
import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostProbe;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.it.agents.HostProcess;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.IOException;
import java.io.OutputStream;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.file.Path;
import java.rmi.registry.LocateRegistry;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 2: the limit on calls before authentication was per client address, so once any
 * local peer had proved the key, 200 connections announcing huge arrays filled a host's heap; and
 * 256 idle connections locked every peer out until they closed. Now a connection may send large
 * calls only once a call on it has proved the key, and a connection that has not yet proved
 * anything makes way for a new one.
 */
class ConnectionFloodIT {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase(Attacker.PASSPHRASE);

    @TempDir
    Path dir;

    @Test
    void idleConnectionsDoNotLockPeersOut() throws Exception {
        Path key = Attacker.keyFile(dir);
        try (HostProcess host = HostProcess.start("idle-flooded", "--key-file", key.toString())) {
            int port = Attacker.port(host.address());
            List<Socket> idle = new ArrayList<>();
            try {
                for (int i = 0; i < 300; i++) {
                    if (i % 2 == 0) {
                        Socket s = new Socket();
                        s.connect(new InetSocketAddress("127.0.0.1", port), 10_000);
                        idle.add(s); // says nothing at all
                    } else {
                        try {
                            idle.add(RawRmi.connect(port)); // says hello, never calls
                        } catch (IOException closedAtOnce) {
                            // beyond the host's limit
                        }
                    }
                }
                try (MwProcess agents = MwProcess.start("idle-flooded-agents", "agents", "--key-file", key.toString(), host.address())) {
                    assertEquals(0, agents.waitFor(Duration.ofSeconds(60)), "a real peer is served while 300 idle connections are held: " + agents.output());
                }
            } finally {
                for (Socket s : idle) {
                    s.close();
                }
            }
            assertTrue(host.alive());
        }
    }

    @Test
    void connectionsAnnouncingHugeArraysCannotFillTheHeapOnceSomePeerProvedTheKey() throws Exception {
        Path key = Attacker.keyFile(dir);
        try (HostProcess host = HostProcess.start("heap-flooded", List.of("-Xmx256m"), "--key-file", key.toString())) {
            CodeArchive archive = HostProbe.archiveOf(ConnectionFloodIT.class);
            assertEquals("OK ", new HostProbe(host.address(), KEY).putArchive(archive.digest(), archive.bytes()),
                    "a real peer on this machine proved the key first");
            int port = Attacker.port(host.address());
            AgentHostRemote stub = (AgentHostRemote) LocateRegistry.getRegistry("127.0.0.1", port).lookup("heap-flooded");
            byte[] call = RawRmi.callAnnouncing(RawRmi.ObjectId.of(stub), "call([B)[B", 40_000_000);
            int connections = 200;
            ExecutorService pool = Executors.newFixedThreadPool(connections);
            List<Socket> open = new ArrayList<>();
            try {
                List<Future<String>> answers = new ArrayList<>();
                for (int i = 0; i < connections; i++) {
                    Socket s = RawRmi.connect(port);
                    open.add(s);
                    OutputStream out = s.getOutputStream();
                    out.write(call);
                    out.write(new byte[1024]); // and then nothing more: the array trickles
                    out.flush();
                    answers.add(pool.submit(() -> RawRmi.answer(s)));
                }
                int refused = 0;
                List<String> others = new ArrayList<>();
                for (Future<String> a : answers) {
                    String answer = a.get(120, TimeUnit.SECONDS);
                    if (answer.contains("REJECTED")) {
                        refused++;
                    } else if (others.size() < 3) {
                        others.add(answer.replaceAll("[^\\x20-\\x7e]", "."));
                    }
                }
                assertEquals(connections, refused, "every connection that proved nothing was refused its huge array before the host read it; others: " + others);
                assertEquals("OK ", new HostProbe(host.address(), KEY).putArchive(archive.digest(), archive.bytes()), "the host still serves a real peer");
            } finally {
                for (Socket s : open) {
                    s.close();
                }
                pool.shutdownNow();
            }
            assertTrue(host.alive());
            assertFalse(host.log().contains("OutOfMemoryError"), "the host never ran out of memory");
        }
    }
}
