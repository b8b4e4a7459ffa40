package io.robomw.it.security;

import io.robomw.testkit.Ports;
import io.robomw.agents.host.rmi.AgentHostRemote;
import io.robomw.it.agents.HostProcess;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.nio.file.Files;
import java.nio.file.Path;
import java.rmi.AccessException;
import java.rmi.RemoteException;
import java.rmi.registry.LocateRegistry;
import java.rmi.registry.Registry;
import java.rmi.server.UnicastRemoteObject;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Issue 37, found 1: another local process could unbind an agent host's name from its RMI
 * registry (every peer then lost it until it restarted) or rebind it to a relay, which a real
 * {@code mw agents} then went through unnoticed while the relay saw every call. Now the registry
 * refuses every change that does not come from the host itself, and a peer's authentication names
 * the address it meant to reach, so a host behind a relay refuses it.
 */
class RegistryRewriteIT {

    @TempDir
    Path dir;

    @Test
    void anotherProcessCanNeitherUnbindNorRebindAHostsName() throws Exception {
        Path key = Attacker.keyFile(dir);
        try (HostProcess host = HostProcess.start("guarded", "--key-file", key.toString())) {
            Registry registry = LocateRegistry.getRegistry("127.0.0.1", Attacker.port(host.address()));
            assertEquals(List.of("guarded"), List.of(registry.list()), "anyone may still look the host up");

            Relay decoyObject = new Relay(null);
            AgentHostRemote decoy = (AgentHostRemote) UnicastRemoteObject.exportObject(decoyObject, 0);
            try {
                assertRefused(assertThrows(RemoteException.class, () -> registry.unbind("guarded")), "unbind");
                assertRefused(assertThrows(RemoteException.class, () -> registry.rebind("guarded", decoy)), "rebind");
                assertRefused(assertThrows(RemoteException.class, () -> registry.bind("other", decoy)), "bind");
            } finally {
                UnicastRemoteObject.unexportObject(decoyObject, true);
            }
            assertEquals(List.of("guarded"), List.of(registry.list()), "the registry is as the host made it");

            try (MwProcess agents = MwProcess.start("registry-rewrite-agents", "agents", "--key-file", key.toString(), host.address())) {
                assertEquals(0, agents.waitFor(Duration.ofSeconds(60)), "a real peer still reaches the host by its name: " + agents.output());
            }
        }
    }

    @Test
    void aPeerGoingThroughARelayIsRefusedAndTheRelaySeesNoCall() throws Exception {
        Path key = Attacker.keyFile(dir);
        try (HostProcess host = HostProcess.start("behind-relay", "--key-file", key.toString())) {
            AgentHostRemote real = (AgentHostRemote) LocateRegistry.getRegistry("127.0.0.1", Attacker.port(host.address())).lookup("behind-relay");
            Relay relay = new Relay(real);
            int relayPort = Ports.free();
            Registry relayRegistry = LocateRegistry.createRegistry(relayPort);
            AgentHostRemote relayStub = (AgentHostRemote) UnicastRemoteObject.exportObject(relay, 0);
            try {
                relayRegistry.rebind("behind-relay", relayStub);
                String throughRelay = "rmi://127.0.0.1:" + relayPort + "/behind-relay";
                int status;
                String printed;
                try (MwProcess agents = MwProcess.start("relayed-agents", "agents", "--key-file", key.toString(), throughRelay)) {
                    status = agents.waitFor(Duration.ofSeconds(60));
                    printed = agents.output();
                }
                assertTrue(relay.authentications.get() > 0, "the peer did go to the relay");
                assertNotEquals(0, status, "the peer did not take the relay for the host: " + printed);
                assertEquals(0, relay.calls.get(), "no call went through the relay");
                // mw agents says a host it cannot ask is DOWN on its listing (stdout), one line naming the address and why
                String log = Files.readString(Path.of("target", "it-logs", "relayed-agents.log"));
                assertTrue(printed.lines().anyMatch(l -> l.contains("DOWN") && l.contains(String.valueOf(relayPort)))
                        && (printed + log).contains("meant to reach"),
                        "the peer says which address the host refused it at: " + printed + log);
                assertTrue(host.log().contains(String.valueOf(relayPort)), "the host logs the address the peer meant to reach");

                try (MwProcess direct = MwProcess.start("direct-agents", "agents", "--key-file", key.toString(), host.address())) {
                    assertEquals(0, direct.waitFor(Duration.ofSeconds(60)), "the host serves the real address: " + direct.output());
                }
            } finally {
                UnicastRemoteObject.unexportObject(relay, true);
                UnicastRemoteObject.unexportObject(relayRegistry, true);
            }
        }
    }

    private static void assertRefused(RemoteException e, String what) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof AccessException) {
                return;
            }
        }
        throw new AssertionError(what + " was not refused with an AccessException: " + e, e);
    }

    /** Passes everything on to a real host, and counts what it saw. */
    static final class Relay implements AgentHostRemote {
        final AtomicInteger authentications = new AtomicInteger();
        final AtomicInteger calls = new AtomicInteger();
        private final AgentHostRemote host;

        Relay(AgentHostRemote host) {
            this.host = host;
        }

        @Override
        public byte[] challenge() throws RemoteException {
            return host == null ? new byte[32] : host.challenge();
        }

        @Override
        public byte[] authenticate(byte[] request) throws RemoteException {
            authentications.incrementAndGet();
            return host == null ? new byte[] {1} : host.authenticate(request);
        }

        @Override
        public byte[] call(byte[] request) throws RemoteException {
            calls.incrementAndGet();
            return host == null ? new byte[0] : host.call(request);
        }
    }
}
