package io.robomw.agents.host.rmi;

import io.robomw.agents.host.ClusterKey;
import io.robomw.agents.host.HostAddress;
import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.security.CallAuthenticator;
import io.robomw.agents.host.wire.WireChannel;
import io.robomw.agents.host.wire.WireFrames;
import io.robomw.agents.host.wire.WireWriter;
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
 *
 * <p><b>Versions.</b> It proposes agent protocol version 5 ({@link Session#COMPACT_VERSION}): version 4
 * ({@link Session#BOUND_VERSION}), whose authentication names the address it meant to reach (the
 * host's RMI address, resolved), so a host behind a relay refuses it and the link fails saying so,
 * and whose host reads agent states in the compact form. A host that takes it names its
 * agent wire's port, and transfers and arrival news then go there ({@link WireChannel}, a few connections kept per
 * link, one call at a time each), every other call over RMI. A host of a build before the compact
 * form refuses 5; the link then authenticates with 4 and agents go to that host in the standard
 * form. A host of a build before version 4 refuses that too; the link then fails saying so, unless
 * it may talk to older builds ({@link #olderHosts()}): it then authenticates again with version 3
 * (and 2 if that is refused, every call over RMI). A link proposes 5 again once it loses the
 * connection (the host may have been upgraded). A wire it cannot
 * connect to (a firewall that lets only the RMI port through) sends that transfer over RMI, and the
 * next ones for {@value #WIRE_RETRY_MILLIS} ms.
 */
public final class PeerLink {

    private static final Logger LOG = LoggerFactory.getLogger(PeerLink.class);

    private final HostAddress address;
    private final String selfName;
    private final ClusterKey key;
    private final HostSockets.Client sockets;
    private final SecureRandom random;
    private final AtomicLong seq = new AtomicLong();
    private final AtomicLong wiresOpened = new AtomicLong();
    private final javax.net.ssl.SSLContext wireTls;
    private final int timeoutMillis;
    /** The idle wire connections, the one used last at the end (taken first, so that those past {@link #MAX_IDLE_WIRES} age at the front). */
    private final java.util.ArrayDeque<WireChannel> idleWires = new java.util.ArrayDeque<>();
    /** Whether a trim of the surplus idle connections is scheduled (guarded by this). */
    private boolean trimScheduled;
    /** One permit per wire connection the link may have in use ({@link #MAX_WIRES}). */
    private final java.util.concurrent.Semaphore wires = new java.util.concurrent.Semaphore(MAX_WIRES, true);
    private AgentHostRemote stub;
    private Session session;
    /** The host's agent wire port for the session, 0 when it offered none. */
    private int wirePort;
    /**
     * The protocol version to propose: 5; 4 after a host refused 5 (a build before the compact form); 3 or 2 after it
     * refused 4 too (only with {@link #olderHosts}); until the link is dropped.
     */
    private int proposeVersion = Session.COMPACT_VERSION;
    /** Whether it may fall back to versions before 4, which do not bind the channel. */
    private boolean olderHosts;
    /** Until when (System.nanoTime) transfers go over RMI because the wire could not be reached; 0: not. */
    private volatile long wireDownUntil;
    /** How long a reply may spin before it blocks, ns. */
    private volatile long wireSpinNanos;
    /** Whether a transfer spins for its reply now. */
    private volatile java.util.function.BooleanSupplier worthSpinning = () -> true;
    private volatile java.util.concurrent.Executor wireTagger;

    /** How long transfers go over RMI after the host's agent wire could not be reached. */
    static final long WIRE_RETRY_MILLIS = 30_000;
    /**
     * The most wire connections a link has open at once: a transfer that finds them all busy waits
     * for one (up to the link's timeout) instead of opening another. Without a bound, a thousand
     * agents leaving at once opened a connection each (a HELLO round trip, a server thread, a
     * backlog slot at the host) and then closed all but the idle ones kept: on a loaded machine the
     * host's accept backlog overflowed, connects timed out, the link fell back to RMI for 30 s and
     * RMI opened a connection per call, past the host's limit (docs/benchmarks.md, "Many agents at once").
     */
    static final int MAX_WIRES = 8;
    /**
     * The most idle wire connections a link keeps for long (half of {@link #MAX_WIRES}), so an idle
     * host holds few sockets and threads for each peer (the soak runs bound what a host keeps after a
     * run: docs/reliability.md). Those past it are kept while they are used at least every
     * {@link #SURPLUS_LINGER_NANOS} and closed after that idle: a sustained load that needs more
     * reuses them rather than closing one at the end of a call and opening another for the next
     * (1,000 agents among 4 hosts opened and closed about 90 connections a second at each host,
     * each with a HELLO, a server thread and a handshake; docs/benchmarks.md, "Many agents at once").
     */
    static final int MAX_IDLE_WIRES = 4;
    /** How long an idle connection past {@link #MAX_IDLE_WIRES} is kept for the next call before it is closed. */
    static final long SURPLUS_LINGER_NANOS = 1_000_000_000L;
    /** An idle wire connection older than this is closed rather than used (the host closes idle ones after 2 minutes). */
    static final long WIRE_STALE_NANOS = 60_000_000_000L;

    public PeerLink(HostAddress address, String selfName, ClusterKey key, HostSockets.Client sockets, SecureRandom random) {
        this(address, selfName, key, sockets, random, null, 10_000);
    }

    /**
     * @param wireTls       the TLS context of agent wire connections (the host's own), or {@code null} for plain ones
     * @param timeoutMillis how long a wire connection may take to connect, and a reply on it to come
     */
    public PeerLink(HostAddress address, String selfName, ClusterKey key, HostSockets.Client sockets, SecureRandom random, javax.net.ssl.SSLContext wireTls,
            int timeoutMillis) {
        this.address = address;
        this.selfName = selfName;
        this.key = key;
        this.sockets = sockets;
        this.random = random;
        this.wireTls = wireTls;
        this.timeoutMillis = timeoutMillis;
    }

    private volatile boolean wireOff;

    /** Sends every call over RMI, even to hosts that offer a wire (a host whose own wire is off). */
    void wireOff() {
        this.wireOff = true;
    }

    /**
     * @param tagger computes the tags of large frames while they are written ({@link WireWriter}), and runs the trims of
     *               surplus idle connections; {@code null}: the writing thread tags, and surplus idle connections are
     *               closed only when the link is next used
     */
    void wireTagger(java.util.concurrent.Executor tagger) {
        this.wireTagger = tagger;
    }

    /**
     * @param spin          how long a transfer waits for its reply by spinning before it blocks (0: never)
     * @param worthSpinning asked at each transfer: whether it spins (the host's {@code fewAgentsLately})
     */
    void wireSpin(java.time.Duration spin, java.util.function.BooleanSupplier worthSpinning) {
        this.wireSpinNanos = spin.toNanos();
        this.worthSpinning = worthSpinning;
    }

    /**
     * Lets the link fall back to agent protocol versions 3 and 2 with a host that refuses 4 (a
     * build before it): those do not bind the channel, so a relay goes unnoticed.
     */
    public synchronized void olderHosts() {
        olderHosts = true;
    }

    /** For tests: proposes only version 2, as peers of builds before the agent wire do. */
    public synchronized void proposeVersion2Only() {
        proposeVersion = Session.PROTOCOL_VERSION;
        version2Only = true;
        session = null;
    }

    /** @return the agent protocol version of the link's session (for tests), 0 before it has one */
    public synchronized int version() {
        return session == null ? 0 : usedVersion;
    }

    /** @return the host's agent wire port the session uses, 0 for none (for tests) */
    public synchronized int wirePort() {
        return wirePort;
    }

    private int usedVersion;

    /** @return the link's session, authenticating first if it has none (for tests) */
    public synchronized Session sessionForTests() throws PeerException {
        return session(0);
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
    public Reply call(Op op, byte[] body) throws PeerException {
        return call(op, Frame.of(body));
    }

    /**
     * @param op    the operation
     * @param frame its body, in a frame this call seals (header and MAC) in place; not to be used by another call meanwhile
     * @return the host's verified reply
     * @throws PeerException if the host cannot be reached, refuses this peer, or the call fails
     */
    public Reply call(Op op, Frame frame) throws PeerException {
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
    public Reply callWithCode(int opCode, byte[] body) throws PeerException {
        return call(opCode, "operation " + opCode, Frame.of(body));
    }

    private Reply call(int opCode, String op, Frame frame) throws PeerException {
        for (int attempt = 0; ; attempt++) {
            Session s;
            AgentHostRemote remote;
            int port;
            synchronized (this) {
                s = session(attempt);
                remote = stub;
                port = wirePort;
            }
            if (onWire(opCode) && port > 0 && !wireOff && (wireDownUntil == 0 || System.nanoTime() - wireDownUntil > 0)) {
                Reply r = callOnWire(s, port, opCode, op, frame);
                if (r == WireChannel.UNKNOWN_SESSION && attempt == 0) {
                    forget(s);
                    continue;
                }
                if (r == WireChannel.UNKNOWN_SESSION) {
                    throw new PeerException("host " + address + " does not know the session it just made: the " + op + " was not served", false, null);
                }
                if (r != null) {
                    return r;
                }
                // the wire could not be reached: this call goes over RMI
            }
            long n = seq.incrementAndGet();
            byte[] raw;
            try {
                s.seal(n, opCode, frame);
                raw = remote.call(frame.exact());
            } catch (RemoteException e) {
                drop();
                if (attempt < 3 && refusedAsUnproven(e)) {
                    // The host restarted and forgot that this host proved the key: it reads only
                    // small calls from it until it authenticates again (HostEndpoint.UNPROVEN_MAX_BYTES).
                    continue;
                }
                throw failure(op, e);
            }
            if (Session.isUnknownSession(raw) && attempt == 0) {
                // The host forgot the session (it keeps a bounded number): it did not serve the call.
                forget(s);
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

    /** @return whether calls with this operation go on the agent wire when the host offers one (transfers, and arrivals: a call per hop or more) */
    private static boolean onWire(int opCode) {
        return opCode == Op.TRANSFER.code() || opCode == Op.ARRIVALS.code();
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

    private synchronized void forget(Session s) {
        if (session == s) {
            session = null;
            closeIdleWires();
        }
    }

    /**
     * A call on the agent wire.
     *
     * @return the verified reply; {@link WireChannel#UNKNOWN_SESSION} if the host does not know the
     *         session (the call was not served); {@code null} if the wire could not be reached (nothing sent)
     * @throws PeerException if the connection failed once the call was sent (it may have been served)
     *                       or the host refused the frame
     */
    private Reply callOnWire(Session s, int port, int opCode, String op, Frame frame) throws PeerException {
        try {
            if (!wires.tryAcquire(timeoutMillis, java.util.concurrent.TimeUnit.MILLISECONDS)) {
                return null; // every connection stayed busy for the whole timeout: this call goes over RMI, the wire stays in use
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new PeerException("interrupted while waiting for an agent wire connection to host " + address + " (the " + op + " was not sent)", false, e);
        }
        try {
            return callOnWireHeld(s, port, opCode, op, frame);
        } finally {
            wires.release();
        }
    }

    /** {@link #callOnWire} with a permit of {@link #wires} held. */
    private Reply callOnWireHeld(Session s, int port, int opCode, String op, Frame frame) throws PeerException {
        WireChannel ch = idleWire(s);
        if (ch == null) {
            try {
                wiresOpened.incrementAndGet();
                ch = WireChannel.connect(s, address.host(), port, wireTls, timeoutMillis, wireTagger);
            } catch (IOException e) {
                wireUnreachable(port, e);
                return null;
            }
            try {
                Reply hello = ch.call(seq.incrementAndGet(), WireFrames.OP_HELLO, new byte[0], 0, 0, 0);
                if (hello == WireChannel.UNKNOWN_SESSION) {
                    ch.close();
                    return hello;
                }
                if (hello.status() != Reply.Status.OK) {
                    throw new IOException("it answered HELLO with " + hello.status() + ": " + hello.text());
                }
            } catch (IOException e) {
                ch.close();
                wireUnreachable(port, e);
                return null;
            }
        }
        Reply r;
        try {
            r = ch.call(seq.incrementAndGet(), opCode, frame.bytes, frame.bodyOffset(), frame.bodyLength(), worthSpinning.getAsBoolean() ? wireSpinNanos : 0);
        } catch (IOException e) {
            ch.close();
            throw new PeerException("cannot reach agent host " + address + " on its agent wire (port " + port + "; the " + op + " may have reached it): "
                    + e.getMessage(), true, e);
        }
        if (r == WireChannel.UNKNOWN_SESSION) {
            ch.close();
            return r;
        }
        giveBack(ch);
        return r;
    }

    private void wireUnreachable(int port, IOException e) {
        wireDownUntil = System.nanoTime() + WIRE_RETRY_MILLIS * 1_000_000L;
        if (wireDownUntil == 0) {
            wireDownUntil = 1;
        }
        LOG.warn("{}: host {}'s agent wire on port {} cannot be reached ({}); its transfers go over RMI for the next {} s", selfName, address, port,
                e.getMessage(), WIRE_RETRY_MILLIS / 1000);
    }

    /** @return an idle wire connection of the session, or {@code null} */
    private synchronized WireChannel idleWire(Session s) {
        WireChannel ch;
        while ((ch = idleWires.pollLast()) != null) {
            if (ch.session == s && ch.idleNanos() < WIRE_STALE_NANOS) {
                return ch;
            }
            ch.close();
        }
        return null;
    }

    private synchronized void giveBack(WireChannel ch) {
        if (ch.session == session && idleWires.size() < MAX_WIRES) {
            idleWires.addLast(ch);
            trimSurplus();
        } else {
            ch.close();
        }
    }

    /**
     * Closes the idle connections past {@link #MAX_IDLE_WIRES} that have lingered unused for
     * {@link #SURPLUS_LINGER_NANOS}; while some are left, a trim is scheduled (on the wire tagger's
     * threads) for when the oldest has lingered, so a link that falls quiet is down to
     * {@link #MAX_IDLE_WIRES} soon after. Called with the lock held.
     */
    private void trimSurplus() {
        while (idleWires.size() > MAX_IDLE_WIRES && idleWires.peekFirst().idleNanos() >= SURPLUS_LINGER_NANOS) {
            idleWires.pollFirst().close();
        }
        java.util.concurrent.Executor on = wireTagger;
        if (idleWires.size() > MAX_IDLE_WIRES && !trimScheduled && on != null) {
            long wait = Math.max(1, SURPLUS_LINGER_NANOS - idleWires.peekFirst().idleNanos());
            try {
                java.util.concurrent.CompletableFuture.delayedExecutor(wait, java.util.concurrent.TimeUnit.NANOSECONDS, on).execute(this::scheduledTrim);
                trimScheduled = true;
            } catch (java.util.concurrent.RejectedExecutionException closing) {
                // the host is closing: its links close their connections
            }
        }
    }

    private synchronized void scheduledTrim() {
        trimScheduled = false;
        trimSurplus();
    }

    /** @return how many wire connections the link has opened (or tried to) so far (for tests) */
    long wiresOpened() {
        return wiresOpened.get();
    }

    /** @return how many idle wire connections the link keeps now (for tests) */
    synchronized int idleWireCount() {
        return idleWires.size();
    }

    private void closeIdleWires() {
        WireChannel ch;
        while ((ch = idleWires.pollFirst()) != null) {
            ch.close();
        }
    }

    /** Forgets the stub and session (and proposes version 5 again: the host may have been upgraded); the next call connects again. */
    public synchronized void drop() {
        stub = null;
        session = null;
        closeIdleWires();
        if (proposeVersion != Session.COMPACT_VERSION && !version2Only) {
            proposeVersion = Session.COMPACT_VERSION;
        }
    }

    private boolean version2Only;

    /** Closes the link's wire connections. */
    synchronized void close() {
        session = null;
        closeIdleWires();
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
            String refusal = authenticate(proposeVersion, attempt);
            while (refusal != null && proposeVersion > Session.PROTOCOL_VERSION && refusal.contains("protocol version " + proposeVersion + ";")) {
                // A host of an older build. The refusal is not authenticated: a relay could forge it to talk the link down to a
                // version that does not bind the channel, so the link goes below 4 only when told it may (5 to 4 costs only the
                // compact form of agent state).
                if (proposeVersion == Session.BOUND_VERSION && !olderHosts) {
                    stub = null;
                    throw new PeerException("host " + address + " does not speak agent protocol version " + Session.BOUND_VERSION + " (" + refusal
                            + "): it is a build older than this one, whose authentication does not name the address it was meant for, so a relay"
                            + " between the hosts would go unnoticed; upgrade it, or let this host talk to older builds (mw host --older-hosts,"
                            + " AgentHostBuilder.olderHosts())", false, null);
                }
                int lower = proposeVersion - 1;
                LOG.info("{}: host {} does not speak agent protocol version {} ({}); using version {}", selfName, address, proposeVersion, refusal, lower);
                proposeVersion = lower;
                refusal = authenticate(proposeVersion, attempt);
            }
            if (refusal != null) {
                stub = null;
                throw new PeerException("host " + address + " refused this peer (" + selfName + "): " + refusal, false, null);
            }
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

    /**
     * One challenge and authentication; sets {@link #session} (and {@link #wirePort}) when accepted.
     *
     * @return {@code null} when accepted, else the host's reason
     * @throws PeerException if the host cannot prove the cluster key, or answers nonsense
     */
    private String authenticate(int version, int attempt) throws IOException, PeerException {
        byte[] hostNonce = stub.challenge();
        byte[] clientNonce = new byte[32];
        random.nextBytes(clientNonce);
        byte[] hostName = address.name().getBytes(StandardCharsets.UTF_8);
        byte[] peerName = selfName.getBytes(StandardCharsets.UTF_8);
        Target target = version >= Session.BOUND_VERSION ? Target.of(address) : null;
        ByteArrayOutputStream req = new ByteArrayOutputStream();
        DataOutputStream out = new DataOutputStream(req);
        int authenticator = CallAuthenticator.DEFAULT;
        byte[] terms = Session.terms(version, authenticator);
        out.writeByte(version);
        out.writeByte(authenticator);
        out.writeUTF(selfName);
        if (target != null) {
            out.write(target.bytes());
        }
        out.write(hostNonce);
        out.write(clientNonce);
        out.write(target == null ? Session.clientProof(key, terms, hostName, peerName, hostNonce, clientNonce)
                : Session.clientProof(key, terms, hostName, peerName, hostNonce, clientNonce, target));
        byte[] answer = stub.authenticate(req.toByteArray());
        if (answer.length == 0 || answer[0] != Session.AUTH_ACCEPTED) {
            return answer.length > 1 ? new String(answer, 1, answer.length - 1, StandardCharsets.UTF_8) : "no reason given";
        }
        boolean offers = version >= Session.WIRE_VERSION;
        int expected = 1 + 8 + 32 + (offers ? 2 : 0);
        if (answer.length != expected) {
            stub = null;
            throw new PeerException("host " + address + " answered the authentication with " + answer.length + " bytes; version " + version
                    + " answers have " + expected, false, null);
        }
        ByteBuffer b = ByteBuffer.wrap(answer, 1, answer.length - 1);
        long id = b.getLong();
        byte[] proof = new byte[32];
        b.get(proof);
        byte[] offer = new byte[offers ? 2 : 0];
        b.get(offer);
        byte[] expectedProof = target != null ? Session.hostProof(key, terms, hostName, peerName, hostNonce, clientNonce, offer, target)
                : offers ? Session.hostProof(key, terms, hostName, peerName, hostNonce, clientNonce, offer)
                : Session.hostProof(key, terms, hostName, peerName, hostNonce, clientNonce);
        if (!MessageDigest.isEqual(proof, expectedProof)) {
            stub = null;
            throw new PeerException("host " + address + " could not prove it knows the cluster key: not sending it anything", false, null);
        }
        closeIdleWires();
        session = new Session(id, Session.sessionKey(key, terms, hostNonce, clientNonce), authenticator);
        usedVersion = version;
        wirePort = offer.length == 2 ? ((offer[0] & 0xFF) << 8) | (offer[1] & 0xFF) : 0;
        LOG.debug("authenticated to {} (session {}, protocol version {}, wire port {}, attempt {})", address, Long.toHexString(id), version, wirePort,
                attempt);
        return null;
    }

    private PeerException failure(String op, Exception e) {
        boolean delivered = !(e instanceof ConnectException || e instanceof ConnectIOException || e instanceof NoSuchObjectException
                || e instanceof NotBoundException || e instanceof UnknownHostException);
        String what = e instanceof NotBoundException ? "nothing is bound as '" + address.name() + "' there"
                : io.robomw.agents.net.RmiSocketSetup.reason(e);
        return new PeerException("cannot reach agent host " + address + (delivered ? " (the " + op + " may have reached it)" : "") + ": " + what, delivered, e);
    }

    @Override
    public String toString() {
        return "PeerLink[" + selfName + " -> " + address + "]";
    }
}
