package io.robomw.agents.host;

import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.HostSockets;
import io.robomw.agents.host.rmi.PeerLink;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.CodeSources;
import io.robomw.agents.host.code.StateCodec;

import java.io.IOException;
import java.io.Serializable;
import java.nio.ByteBuffer;
import java.security.SecureRandom;
import java.util.UUID;

/**
 * Test tool: speaks to an agent host as an authenticated peer but sends what a test chooses, such
 * as state streams and archives a real host would never send. Shared with src-it through the
 * test-jar.
 */
public final class HostProbe {

    private final PeerLink link;

    /**
     * @param address the host
     * @param key     the cluster key to prove
     */
    public HostProbe(String address, ClusterKey key) {
        HostAddress a = HostAddress.parse(address);
        this.link = new PeerLink(a, "probe", key, new HostSockets.Client(a.host(), false, 10_000), new SecureRandom());
    }

    /**
     * @param agentClass a class whose code location becomes the archive
     * @return that archive
     */
    public static CodeArchive archiveOf(Class<?> agentClass) {
        return new CodeSources().archiveOf(agentClass);
    }

    /**
     * @param value an agent or anything serializable
     * @return its serialized form
     * @throws IOException if it is not serializable
     */
    public static byte[] state(Serializable value) throws IOException {
        return StateCodec.write(value);
    }

    /**
     * @param claimed the digest to claim
     * @param jar     the bytes to send
     * @return the host's answer: its status, a space, and its text
     * @throws IOException if the host cannot be reached
     */
    public String putArchive(CodeArchive.Digest claimed, byte[] jar) throws IOException {
        byte[] d = claimed.bytes();
        Reply r = link.call(Op.PUT_ARCHIVE, ByteBuffer.allocate(d.length + jar.length).put(d).put(jar).array());
        return r.status() + " " + r.text();
    }

    /**
     * Sends a transfer of the given state, as hop 1 of a new agent whose home is nowhere.
     *
     * @param digest    the archive the state's classes come from
     * @param className the class to name in the header
     * @param state     the state stream
     * @return the host's answer: its status, a space, and its text
     * @throws IOException if the host cannot be reached
     */
    public String transfer(CodeArchive.Digest digest, String className, byte[] state) throws IOException {
        Reply r = link.call(Op.TRANSFER, image(digest, state));
        return r.status() + " " + r.text();
    }

    /**
     * Sends a call with any operation code and body, as no honest peer would.
     *
     * @param opCode the operation byte (the known ones are 0-10)
     * @param body   the body
     * @return the host's answer: its status, a space, and its text
     * @throws IOException if the host cannot be reached
     */
    public String call(int opCode, byte[] body) throws IOException {
        Reply r = link.callWithCode(opCode, body);
        return r.status() + " " + r.text();
    }

    /**
     * @param digest the archive the state's classes come from
     * @param state  the state stream
     * @return a transfer's body: the image of hop 1 of a new agent whose home is nowhere (its first byte is the kind code)
     */
    public static byte[] image(CodeArchive.Digest digest, byte[] state) {
        return new AgentImage(UUID.randomUUID(), 1, AgentImage.Kind.TRIP, false, "rmi://127.0.0.1:1/probe-home", digest, 1, state).encode();
    }
}
