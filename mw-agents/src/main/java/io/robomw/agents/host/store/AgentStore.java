package io.robomw.agents.host.store;

import io.robomw.agents.host.code.CodeArchive;

import java.io.IOException;
import java.util.List;
import java.util.Optional;
import java.util.UUID;

/**
 * Where a host keeps the agents it has accepted, until the next host has them, and the results
 * it owes their homes, until the home has them. {@link JournalStore} survives the host being
 * killed; {@link MemoryStore} does not, and is for speed.
 *
 * <p>The order of one hop at the receiving host: {@link #accepted} (durable before the sender is
 * acknowledged), {@link #started} (durable before the stop's work begins, so the work never runs
 * twice), {@link #departing} with the state after the work, {@link #departed} once the next host
 * has acknowledged (only that copy: a hop to this same host has stored the next one already).
 * A transfer's agent, whose runner waits for it, is stored with {@link #acceptedStarting}: the
 * first two in one durable write. Thread-safe.
 */
public interface AgentStore extends AutoCloseable {

    /** Where an agent stood when the host last wrote it down. */
    enum Phase {
        /** Accepted, its stop not started. */
        ACCEPTED,
        /** Its stop's work had begun. */
        STARTED,
        /** Its stop done, being sent on. */
        DEPARTING
    }

    /**
     * An agent the host holds.
     *
     * @param id    the agent
     * @param hop   the hop that brought it (or, when departing, the hop that takes it on)
     * @param phase where it stood
     * @param image its travelling form
     */
    record StoredAgent(UUID id, long hop, Phase phase, byte[] image) {
    }

    /**
     * A result or report a home has not acknowledged yet.
     *
     * @param id        the agent
     * @param seq       its order among that agent's events
     * @param owedSince when the host began to owe it, in milliseconds since the epoch (its age
     *                  counts from there, across restarts, for the delivery's expiry)
     * @param event     the encoded event
     */
    record PendingEvent(UUID id, long seq, long owedSince, byte[] event) {
    }

    /** @return whether this store survives the host being killed */
    boolean durable();

    /** @return where this store keeps agents, for messages: its journal file, or "memory" */
    String location();

    /**
     * @param id     the agent
     * @param hop    the hop that brought it
     * @param image  holds its travelling form (a store that keeps it copies it)
     * @param offset where the travelling form starts in {@code image}
     * @param length its length
     * @throws IOException if it cannot be stored (the hop must then be refused)
     */
    void accepted(UUID id, long hop, byte[] image, int offset, int length) throws IOException;

    /**
     * {@link #accepted} and {@link #started} at once, for an agent whose stop begins as soon as it
     * is stored (a transfer's: its runner is waiting): durable before return, in one write and one
     * {@code fdatasync} in a store that forces them, where the two calls take two. From then on
     * the stop counts as begun: a host that dies before its work actually begins (the
     * microseconds between this call and the stop's first line) does not run it after a restart,
     * as for a host that dies during the work. Stops run at most once either way.
     *
     * @param id     the agent
     * @param hop    the hop that brought it
     * @param image  holds its travelling form
     * @param offset where the travelling form starts in {@code image}
     * @param length its length
     * @throws IOException if it cannot be stored (the hop must then be refused)
     */
    default void acceptedStarting(UUID id, long hop, byte[] image, int offset, int length) throws IOException {
        accepted(id, hop, image, offset, length);
        started(id, hop);
    }

    /**
     * @param id  the agent
     * @param hop its current hop
     * @throws IOException if it cannot be written (the work must then not start)
     */
    void started(UUID id, long hop) throws IOException;

    /**
     * @param id     the agent
     * @param hop    the hop that takes it on
     * @param image  holds its travelling form after the stop (a store that keeps it copies it)
     * @param offset where the travelling form starts in {@code image}
     * @param length its length
     * @throws IOException if it cannot be written
     */
    void departing(UUID id, long hop, byte[] image, int offset, int length) throws IOException;

    /**
     * Forgets the copy of an agent that left this host with {@code hop} (the next host has
     * acknowledged it), or ended here: unless what is held of the agent came with that hop or a
     * later one. That happens on a hop to this same host, which stores the new copy (with the
     * same hop) before the sender records the old one departed, and when the agent comes back
     * before its sender gets to this call: the new copy must survive a restart.
     *
     * @param id  the agent, now stored by the next host or ended here
     * @param hop the hop that took it on ({@link #departing}'s); for an agent that ended here, one
     *            past the hop that brought it
     * @throws IOException if it cannot be written
     */
    void departed(UUID id, long hop) throws IOException;

    /**
     * @param id the agent
     * @return the highest hop of it this host ever accepted, or -1
     */
    long highestHop(UUID id);

    /**
     * The number an agent held here gives its next report or result: one past the highest of the
     * events this store recorded it owing since it arrived, or 0 if none (then its image's number
     * stands). An agent resumed after a restart numbers on from the larger of the two, so its home,
     * which drops numbers it has seen, never takes a new report for a repeat.
     *
     * @param id the agent
     * @return the next number, or 0
     */
    long nextEventSeq(UUID id);

    /**
     * @param event an event owed to a home (durable before return)
     * @throws IOException if it cannot be written
     */
    void eventPending(PendingEvent event) throws IOException;

    /**
     * @param id  the agent
     * @param seq the event the home acknowledged
     * @throws IOException if it cannot be written
     */
    void eventDelivered(UUID id, long seq) throws IOException;

    /**
     * @param archive an archive of agent code (durable before return)
     * @throws IOException if it cannot be written
     */
    void putArchive(CodeArchive archive) throws IOException;

    /**
     * @param digest an archive's digest
     * @return the archive, if this store has it
     */
    Optional<CodeArchive> archive(CodeArchive.Digest digest);

    /** @return the agents held when the store was opened (after a restart: the ones to resume) */
    List<StoredAgent> recoveredAgents();

    /** @return the events owed to homes when the store was opened */
    List<PendingEvent> recoveredEvents();

    @Override
    void close() throws IOException;
}
