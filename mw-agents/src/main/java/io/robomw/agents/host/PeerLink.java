package io.robomw.agents.host;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.rmi.ConnectException;
import java.rmi.ConnectIOException;
import java.rmi.NoSuchObjectException;
import java.rmi.NotBoundException;
import java.rmi.RemoteException;
import java.rmi.UnknownHostException;
import java.rmi.registry.LocateRegistry;
import java.rmi.registry.Registry;
import java.security.MessageDigest;
import java.security.SecureRandom;
import java.util.concurrent.atomic.AtomicLong;

/**
 * This host's authenticated link to one other host: looks its stub up, proves the cluster key,
 * checks the host's proof in turn, and makes MAC'd calls on the session. A lost session (the host
 * restarted) is made again once per call; a failed call drops the stub so the next call looks it
 * up afresh. Thread-safe: calls from several threads share the session.
 */
final class PeerLink {

    private static final Logger LOG = LoggerFactory.getLogger(PeerLink.class);

    private final HostAddress address;
    private final String selfName;
    private final ClusterKey key;
    private final HostSockets.Client sockets;
    private final SecureRandom random;
    private final AtomicLong seq = new AtomicLong();
    private AgentHostRemote stub;
    private Session session;

    PeerLink(HostAddress address, String selfName, ClusterKey key, HostSockets.Client sockets, SecureRandom random) {
        this.address = address;
        this.selfName = selfName;
        this.key = key;
        this.sockets = sockets;
        this.random = random;
    }

    HostAddress address() {
        return address;
    }

    /**
     * @param op   the operation
     * @param body its body
     * @return the host's verified reply
     * @throws PeerException if the host cannot be reached, refuses this peer, or the call fails
     */
    Reply call(Op op, byte[] body) throws PeerException {
        return call(op, Frame.of(body));
    }

    /**
     * @param op    the operation
     * @param frame its body, in a frame this call seals (header and MAC) in place; not to be used by another call meanwhile
     * @return the host's verified reply
     * @throws PeerException if the host cannot be reached, refuses this peer, or the call fails
     */
    Reply call(Op op, Frame frame) throws PeerException {
        return call(op.code(), op.name(), frame);
    }

    /**
     * A call with an operation code that may be none of {@link Op}'s: for probes that check how a
     * host answers codes it does not know.
     *
     * @param opCode the operation byte to send
     * @param body   the body
     * @return the host's verified reply
     * @throws PeerException if the host cannot be reached, refuses this peer, or the call fails
     */
    Reply callWithCode(int opCode, byte[] body) throws PeerException {
        return call(opCode, "operation " + opCode, Frame.of(body));
    }

    private Reply call(int opCode, String op, Frame frame) throws PeerException {
        for (int attempt = 0; ; attempt++) {
            Session s;
            AgentHostRemote remote;
            synchronized (this) {
                s = session(attempt);
                remote = stub;
            }
            long n = seq.incrementAndGet();
            byte[] raw;
            try {
                s.seal(n, opCode, frame);
                raw = remote.call(frame.bytes);
            } catch (RemoteException e) {
                drop();
                if (attempt == 0 && refusedAsUnproven(e)) {
                    // The host restarted and forgot that this host proved the key: it reads only
                    // small calls from it until it authenticates again (HostEndpoint.UNPROVEN_MAX_BYTES).
                    continue;
                }
                throw failure(op, e);
            }
            if (Session.isUnknownSession(raw) && attempt == 0) {
                // The host forgot the session (it keeps a bounded number): it did not serve the call.
                synchronized (this) {
                    if (session == s) {
                        session = null;
                    }
                }
                continue;
            }
            try {
                return s.verifyReply(n, raw);
            } catch (RuntimeException e) {
                drop();
                throw new PeerException("host " + address + " sent a bad reply to " + op + ": " + e.getMessage(), true, e);
            }
        }
    }

    /** @return whether the host's deserialization filter refused the call's arguments (too large before authentication) */
    private static boolean refusedAsUnproven(Throwable e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof java.io.InvalidClassException && String.valueOf(t.getMessage()).contains("REJECTED")) {
                return true;
            }
        }
        return false;
    }

    /** Forgets the stub and session; the next call connects again. */
    synchronized void drop() {
        stub = null;
        session = null;
    }

    private Session session(int attempt) throws PeerException {
        if (session != null) {
            return session;
        }
        try {
            if (stub == null) {
                Registry registry = LocateRegistry.getRegistry(address.host(), address.port(), sockets);
                stub = (AgentHostRemote) registry.lookup(address.name());
            }
            byte[] hostNonce = stub.challenge();
            byte[] clientNonce = new byte[32];
            random.nextBytes(clientNonce);
            byte[] hostName = address.name().getBytes(StandardCharsets.UTF_8);
            byte[] peerName = selfName.getBytes(StandardCharsets.UTF_8);
            ByteArrayOutputStream req = new ByteArrayOutputStream();
            DataOutputStream out = new DataOutputStream(req);
            int authenticator = CallAuthenticator.DEFAULT;
            byte[] terms = Session.terms(Session.PROTOCOL_VERSION, authenticator);
            out.writeByte(Session.PROTOCOL_VERSION);
            out.writeByte(authenticator);
            out.writeUTF(selfName);
            out.write(hostNonce);
            out.write(clientNonce);
            out.write(Session.clientProof(key, terms, hostName, peerName, hostNonce, clientNonce));
            byte[] answer = stub.authenticate(req.toByteArray());
            if (answer.length == 0 || answer[0] != Session.AUTH_ACCEPTED) {
                String why = answer.length > 1 ? new String(answer, 1, answer.length - 1, StandardCharsets.UTF_8) : "no reason given";
                stub = null;
                throw new PeerException("host " + address + " refused this peer (" + selfName + "): " + why, false, null);
            }
            ByteBuffer b = ByteBuffer.wrap(answer, 1, answer.length - 1);
            long id = b.getLong();
            byte[] proof = new byte[32];
            b.get(proof);
            if (!MessageDigest.isEqual(proof, Session.hostProof(key, terms, hostName, peerName, hostNonce, clientNonce))) {
                stub = null;
                throw new PeerException("host " + address + " could not prove it knows the cluster key: not sending it anything", false, null);
            }
            session = new Session(id, Session.sessionKey(key, terms, hostNonce, clientNonce), authenticator);
            LOG.debug("authenticated to {} (session {}, attempt {})", address, Long.toHexString(id), attempt);
            return session;
        } catch (RemoteException | NotBoundException e) {
            stub = null;
            PeerException f = failure(Op.TRANSFER.name(), e);
            throw new PeerException(f.getMessage().replace(" (the TRANSFER may have reached it)", ""), false, e);
        } catch (IOException e) {
            stub = null;
            throw new PeerException("cannot authenticate to " + address + ": " + e.getMessage(), false, e);
        } catch (ClassCastException e) {
            stub = null;
            throw new PeerException(address + " is not an agent host", false, e);
        }
    }

    private PeerException failure(String op, Exception e) {
        boolean delivered = !(e instanceof ConnectException || e instanceof ConnectIOException || e instanceof NoSuchObjectException
                || e instanceof NotBoundException || e instanceof UnknownHostException);
        String what = e instanceof NotBoundException ? "nothing is bound as '" + address.name() + "' there" : String.valueOf(e.getMessage());
        return new PeerException("cannot reach agent host " + address + (delivered ? " (the " + op + " may have reached it)" : "") + ": " + what, delivered, e);
    }

    @Override
    public String toString() {
        return "PeerLink[" + selfName + " -> " + address + "]";
    }
}
