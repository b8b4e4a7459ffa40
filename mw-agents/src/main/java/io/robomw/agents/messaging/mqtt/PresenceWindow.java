package io.robomw.agents.messaging.mqtt;

import io.robomw.agents.messaging.PresenceRecord;
import io.robomw.agents.messaging.security.ReplayStore;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.time.Duration;
import java.util.HashMap;
import java.util.Map;

/**
 * A directory's replay window for signed presences: a presence captured earlier and published
 * again at the broker (retained, where every later reader gets it) is not believed. Per announcing
 * client (at one broker, under one prefix) it keeps the newest connection taken
 * ({@link PresenceRecord#since()}, the time of the client's will, which every record of that
 * connection carries) and, of that connection, the newest record's time. Refused, as stale:
 * <ul>
 * <li>a record of an earlier connection than one taken (an old host's "offline", or an old
 *     "online" naming an address it no longer has, replayed after it reconnected);</li>
 * <li>an online record of the taken connection older than the newest taken of it.</li>
 * </ul>
 * The connection's will (offline, its time the connection's start) is taken whenever it comes,
 * as MQTT's will is meant to be. Both are kept per client in a {@link ReplayStore} (two entries),
 * so a reader that restarts still refuses what it would have refused before (as a receiver's message window does, docs/security.md).
 *
 * <p>What it does not do: refuse a replay to a reader that never took a newer record of that
 * client, nor the will of the live connection published early by someone who read it off an
 * unencrypted network (a will travels in the client's CONNECT: use {@code mqtts://} there). A node
 * whose clock went back across a restart is refused until its new connection's time passes the
 * old one (or {@link #KEEP} after the reader last took a record of it). Thread-safe.
 */
final class PresenceWindow {

    /** How long the reader remembers a client's newest connection after it last took a record of it. */
    static final Duration KEEP = Duration.ofDays(30);

    private record Taken(long since, long time) {
    }

    private final String where;
    private final ReplayStore store;
    private final Map<String, Taken> taken = new HashMap<>();

    /**
     * @param where the broker's endpoint and prefix: clients of the same identifier at other brokers are other clients
     * @param store where the newest connection per client is kept across restarts ({@link ReplayStore#memoryOnly()} for nowhere)
     */
    PresenceWindow(String where, ReplayStore store) {
        this.where = where;
        this.store = store;
    }

    /**
     * @param client    the client whose presence topic the record came on
     * @param record    the record, signed with the cluster's seal
     * @param nowMillis this reader's clock
     * @return whether to take it ({@code false}: it is stale, a replay)
     */
    synchronized boolean take(String client, PresenceRecord record, long nowMillis) {
        long since = record.since().toEpochMilli();
        long time = record.time().toEpochMilli();
        long sinceSource = source(client, "since");
        long timeSource = source(client, "time");
        Taken t = taken.get(client);
        if (t == null) {
            // what a run of this reader before this start took, if anything
            t = new Taken(store.floor(sinceSource), store.floor(timeSource));
        }
        if (since < t.since()) {
            return false;
        }
        boolean sameConnection = since == t.since();
        if (sameConnection && record.online() && time < t.time()) {
            return false;
        }
        taken.put(client, new Taken(since, sameConnection ? Math.max(t.time(), time) : time));
        store.record(sinceSource, since, nowMillis);
        store.record(timeSource, time, nowMillis);
        return true;
    }

    private long source(String client, String what) {
        try {
            byte[] h = MessageDigest.getInstance("SHA-256").digest((where + "\n" + client + "\n" + what).getBytes(StandardCharsets.UTF_8));
            return ByteBuffer.wrap(h).getLong();
        } catch (NoSuchAlgorithmException e) {
            throw new IllegalStateException("SHA-256 is missing from this JVM", e);
        }
    }
}
