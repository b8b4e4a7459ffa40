package io.robomw.agents.host;

import io.robomw.agents.host.rmi.AgentHostRemote;
import io.robomw.agents.host.rmi.HostEndpoint;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.Session;
import io.robomw.agents.host.code.CodeArchive;
import org.junit.jupiter.api.Test;

import java.io.InvalidClassException;
import java.rmi.RemoteException;
import java.rmi.registry.LocateRegistry;

import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * Before a peer has proved the cluster key, its calls may carry only small arrays: a large one is
 * refused by the deserialization filter before it is read (issue 15: 8 parallel 60 MiB calls
 * without the key grew a host's RSS by 140 MB). Once a peer at that address has proved the key,
 * large calls are read again.
 */
class UnprovenCallsTest {

    private static final ClusterKey KEY = ClusterKey.fromPassphrase("unproven calls");

    @Test
    void largeCallsAreReadOnlyFromHostsWhosePeerProvedTheKey() throws Exception {
        try (AgentHost host = AgentHost.builder("guarded").clusterKey(KEY).start()) {
            HostAddress a = HostAddress.parse(host.address());
            AgentHostRemote stranger = (AgentHostRemote) LocateRegistry.getRegistry(a.host(), a.port(), new HostSockets.Client(a.host(), false, 10_000))
                    .lookup(a.name());

            RemoteException tooLarge = assertThrows(RemoteException.class, () -> stranger.call(new byte[1 << 20]));
            assertTrue(refusedByTheFilter(tooLarge), "refused before it was read: " + tooLarge);
            assertThrows(RemoteException.class, () -> stranger.authenticate(new byte[HostEndpoint.UNPROVEN_MAX_BYTES + 1]));
            assertTrue(Session.isUnknownSession(stranger.call(new byte[1000])), "a small call is read, and answered: no such session");

            HostProbe peer = new HostProbe(host.address(), KEY);
            byte[] large = new byte[200_000];
            String answer = peer.putArchive(CodeArchive.Digest.of(new byte[] {1}), large);
            assertTrue(answer.startsWith("REFUSED"), "the proved peer's large call was read and answered: " + answer);
        }
    }

    /**
     * The filter's refusal reaches the caller as the host's answer (InvalidClassException REJECTED), or, when
     * the host refuses and closes the connection while the caller is still writing the large array (JDK 25
     * does so), as a broken connection while marshalling: either way the host did not read the array. A
     * client connection sends a call in one write at RMI's flush ({@link HostSockets#COALESCE_MAX_BYTES}),
     * which RMI does as it starts to read the answer, so the broken connection may also come as an error
     * "unmarshaling return header" whose cause is the write's broken pipe.
     */
    private static boolean refusedByTheFilter(Throwable e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof InvalidClassException && String.valueOf(t.getMessage()).contains("REJECTED")) {
                return true;
            }
        }
        if (e instanceof java.rmi.MarshalException && e.getCause() instanceof java.net.SocketException) {
            return true;
        }
        return e instanceof java.rmi.UnmarshalException && e.getCause() instanceof java.net.SocketException s
                && String.valueOf(s.getMessage()).contains("Broken pipe");
    }
}
