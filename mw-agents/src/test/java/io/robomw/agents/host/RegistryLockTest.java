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

    private static void refused(RemoteException e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof AccessException) {
                return;
            }
        }
        throw new AssertionError("not refused with an AccessException: " + e, e);
    }
}
