package io.robomw.agents.host;

import org.junit.jupiter.api.Test;

import java.rmi.AccessException;
import java.rmi.Remote;
import java.rmi.RemoteException;
import java.rmi.registry.LocateRegistry;
import java.rmi.registry.Registry;
import java.rmi.server.UnicastRemoteObject;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

/**
 * Issue 37: an agent host's registry takes no bind, rebind or unbind from outside the host, even
 * from this machine (the JDK's own registry lets local callers change it, and refuses callers of
 * unknown origin, which is what the host's sockets make every caller). A guard against a JDK that
 * changes this: every build runs it, on the newest JDK too.
 */
class RegistryLockTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("registry lock");

    @Test
    void theRegistryRefusesEveryChangeFromACallerAndStillAnswersLookups() throws Exception {
        try (AgentHost host = AgentHost.builder("locked").clusterKey(KEY).noMessaging().start()) {
            HostAddress a = HostAddress.parse(host.address());
            Registry registry = LocateRegistry.getRegistry(a.host(), a.port());
            assertEquals(List.of("locked"), List.of(registry.list()));
            Remote decoyObject = new AgentHostRemote() {
                @Override
                public byte[] challenge() {
                    return new byte[32];
                }

                @Override
                public byte[] authenticate(byte[] request) {
                    return new byte[] {Session.AUTH_REFUSED};
                }

                @Override
                public byte[] call(byte[] request) {
                    return new byte[0];
                }
            };
            Remote decoy = UnicastRemoteObject.exportObject(decoyObject, 0);
            try {
                refused(assertThrows(RemoteException.class, () -> registry.unbind("locked")));
                refused(assertThrows(RemoteException.class, () -> registry.rebind("locked", decoy)));
                refused(assertThrows(RemoteException.class, () -> registry.bind("other", decoy)));
            } finally {
                UnicastRemoteObject.unexportObject(decoyObject, true);
            }
            assertEquals(List.of("locked"), List.of(registry.list()));
            assertEquals(Reply.Status.OK, new PeerLink(a, "probe", KEY, new HostSockets.Client(a.host(), false, 10_000), new java.security.SecureRandom())
                    .call(Op.LIST, new byte[0]).status(), "peers still find the host by its name");
        }
    }

    /**
     * Over TLS the host knows which connection a call comes on too (the TLS layer reads the counted
     * socket on RMI's connection thread): a large call on a connection that proved the key is read.
     */
    @Test
    void aTlsHostReadsALargeCallOnAConnectionThatProvedTheKey(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir) throws Exception {
        io.robomw.agents.messaging.TestKeys keys = io.robomw.agents.messaging.TestKeys.create(dir);
        javax.net.ssl.SSLContext before = javax.net.ssl.SSLContext.getDefault();
        javax.net.ssl.SSLContext.setDefault(keys.node().context());
        try (AgentHost host = AgentHost.builder("tls-locked").tls(keys.node()).clusterKey(KEY).noMessaging().wire(false).start()) {
            HostAddress a = HostAddress.parse(host.address());
            PeerLink peer = new PeerLink(a, "probe", KEY, new HostSockets.Client(a.host(), true, 10_000), new java.security.SecureRandom());
            byte[] large = new byte[32 + 300_000];
            Reply r = peer.call(Op.PUT_ARCHIVE, large);
            assertEquals(Reply.Status.REFUSED, r.status(), "read and answered (the archive is no jar): " + r.text());
        } finally {
            javax.net.ssl.SSLContext.setDefault(before);
        }
    }

    private static void refused(RemoteException e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof AccessException) {
                return;
            }
        }
        throw new AssertionError("not refused with an AccessException: " + e, e);
    }
}
