package io.robomw.agents.host.store;

import io.robomw.agents.host.code.CodeArchive;

import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;

/** An {@link AgentStore} in memory only: fast, and lost with the host. Thread-safe. */
public final class MemoryStore implements AgentStore {

    private static final int SEEN_CAPACITY = 100_000;

    private final Map<CodeArchive.Digest, CodeArchive> archives = new ConcurrentHashMap<>();
    private final Map<UUID, Long> seen = new LinkedHashMap<>(256, 0.75f, true) {
        private static final long serialVersionUID = 1L;

        @Override
        protected boolean removeEldestEntry(Map.Entry<UUID, Long> eldest) {
            return size() > SEEN_CAPACITY;
        }
    };

    @Override
    public boolean durable() {
        return false;
    }

    @Override
    public String location() {
        return "memory";
    }

    @Override
    public void accepted(UUID id, long hop, byte[] image, int offset, int length) {
        synchronized (seen) {
            seen.merge(id, hop, Math::max);
        }
    }

    @Override
    public void started(UUID id, long hop) {
    }

    @Override
    public void departing(UUID id, long hop, byte[] image, int offset, int length) {
    }

    @Override
    public void departed(UUID id, long hop) {
    }

    @Override
    public long highestHop(UUID id) {
        synchronized (seen) {
            return seen.getOrDefault(id, -1L);
        }
    }

    /** A memory store resumes nothing: the agent's own number always stands. */
    @Override
    public long nextEventSeq(UUID id) {
        return 0;
    }

    @Override
    public void eventPending(PendingEvent event) {
    }

    @Override
    public void eventDelivered(UUID id, long seq) {
    }

    @Override
    public void putArchive(CodeArchive archive) {
        archives.putIfAbsent(archive.digest(), archive);
    }

    @Override
    public Optional<CodeArchive> archive(CodeArchive.Digest digest) {
        return Optional.ofNullable(archives.get(digest));
    }

    @Override
    public List<StoredAgent> recoveredAgents() {
        return List.of();
    }

    @Override
    public List<PendingEvent> recoveredEvents() {
        return List.of();
    }

    @Override
    public void close() {
    }
}
