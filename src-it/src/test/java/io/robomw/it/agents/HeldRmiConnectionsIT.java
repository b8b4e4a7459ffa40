package io.robomw.it.agents;

import io.robomw.agents.host.HostProbe;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.trip.VisitorAgent;
import io.robomw.testkit.Await;
import io.robomw.it.soak.HostFigures;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * A peer that holds hundreds of RMI connections to an agent host and lets them go must not leave
 * the host holding a thread for each (issue 15: 300 held connections left 326 threads three
 * seconds after closing: RMI keeps an idle connection thread for a minute). {@code mw host} in
 * its own JVM, with the RMI settings {@code mw} gives it (idle connection threads end after 5 s,
 * Mw.boundRmiConnections); 300 connections each complete RMI's JRMP handshake and are held, then
 * closed; the host's threads (from /proc) come back to their baseline within 30 s, well before
 * the JDK's default minute.
 */
class HeldRmiConnectionsIT {

    private static final int CONNECTIONS = 300;
    /** JRMP: the magic "JRMI", version 2, the stream protocol; the host answers ProtocolAck. */
    private static final int JRMP_MAGIC = 0x4a524d49;
    private static final int JRMP_VERSION = 2;
    private static final int STREAM_PROTOCOL = 0x4b;
    private static final int PROTOCOL_ACK = 0x4e;

    @TempDir
    Path dir;

    @Test
    void threadsOfThreeHundredHeldConnectionsEndSoonAfterTheyClose() throws Exception {
        try (HostProcess host = HostProcess.start("held-connections", "--key-file", AgentTripIT.keyFile(dir).toString())) {
            int port = Integer.parseInt(host.address().replaceAll("^rmi://[^:]+:(\\d+)/.*$", "$1"));
            int baseline = threads(host);
            List<Socket> held = new ArrayList<>();
            int accepted = 0;
            try {
                for (int i = 0; i < CONNECTIONS; i++) {
                    Socket s = new Socket();
                    held.add(s);
                    if (handshake(s, port)) {
                        accepted++;
                    }
                }
                int whileHeld = threads(host);
                assertTrue(accepted >= 200, "the host took at least 200 of the " + CONNECTIONS + " connections (its limit is 256): " + accepted);
                assertTrue(whileHeld >= baseline + 200,
                        "the held connections cost the host a thread each: " + whileHeld + " threads, baseline " + baseline + ", " + accepted + " accepted");
            } finally {
                for (Socket s : held) {
                    s.close();
                }
            }
            long closed = System.nanoTime();
            int[] last = {0};
            Await.until("the host's threads back within 16 of its baseline " + baseline + " after the " + accepted + " connections closed",
                    Duration.ofSeconds(30), () -> (last[0] = threads(host)) <= baseline + 16, () -> "(last " + last[0] + " threads)");
            System.out.printf("held RMI connections: %d accepted, threads baseline %d, back to %d after %d ms%n",
                    accepted, baseline, last[0], (System.nanoTime() - closed) / 1_000_000);
            assertTrue(host.alive(), "the host still runs");
            CodeArchive archive = HostProbe.archiveOf(VisitorAgent.class);
            assertEquals("OK ", new HostProbe(host.address(), AgentTripIT.KEY).putArchive(archive.digest(), archive.bytes()),
                    "the host still serves a peer with the key");
        }
    }

    /** Connects and does JRMP's handshake as an RMI client does; false if the host closed it instead (beyond its limit). */
    private static boolean handshake(Socket s, int port) throws IOException {
        s.connect(new InetSocketAddress("127.0.0.1", port), 10_000);
        s.setSoTimeout(30_000);
        DataOutputStream out = new DataOutputStream(s.getOutputStream());
        DataInputStream in = new DataInputStream(s.getInputStream());
        int ack;
        try {
            out.writeInt(JRMP_MAGIC);
            out.writeShort(JRMP_VERSION);
            out.writeByte(STREAM_PROTOCOL);
            out.flush();
            ack = in.read();
        } catch (IOException closedByTheHost) {
            return false;
        }
        if (ack == -1) {
            return false;
        }
        assertEquals(PROTOCOL_ACK, ack, "JRMP ProtocolAck");
        in.readUTF(); // the host as the server sees the client
        in.readInt(); // and its port
        out.writeUTF("127.0.0.1"); // the client's endpoint, as RMI's client sends it
        out.writeInt(0);
        out.flush();
        return true;
    }

    private static int threads(HostProcess host) {
        try {
            return HostFigures.threadsOf(host.pid());
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
