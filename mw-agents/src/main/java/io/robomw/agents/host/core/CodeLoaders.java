package io.robomw.agents.host.core;

import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.code.ArchiveClassLoader;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.CodeSources;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Agents' code at a host: the archives of agents sent from here ({@link #archiveOf}), the archives
 * peers send ({@link #onArchive}, checked against their digest and kept in the store), and one
 * class loader per archive, made once and kept for every agent of that code. Thread-safe.
 */
public final class CodeLoaders {

    private static final Logger LOG = LoggerFactory.getLogger(CodeLoaders.class);

    private final HostState host;
    private final CodeSources sources = new CodeSources();
    private final Map<CodeArchive.Digest, ArchiveClassLoader> loaders = new ConcurrentHashMap<>();

    public CodeLoaders(HostState host) {
        this.host = host;
    }

    /**
     * The archive of an agent's code, kept in the store so that hosts that lack it can be sent it.
     *
     * @param type the agent's class
     * @return its archive
     * @throws UncheckedIOException if the store cannot keep it
     */
    public CodeArchive archiveOf(Class<?> type) {
        CodeArchive archive = sources.archiveOf(type);
        try {
            host.store.putArchive(archive);
        } catch (IOException e) {
            throw new UncheckedIOException("cannot keep the archive of " + type.getName() + ": " + e.getMessage(), e);
        }
        return archive;
    }

    /**
     * @param digest an archive's digest
     * @return the class loader of that archive, if the host has the archive
     * @throws IOException if the stored archive is not a jar
     */
    public Optional<ClassLoader> loaderFor(CodeArchive.Digest digest) throws IOException {
        ArchiveClassLoader l = loaders.get(digest);
        if (l != null) {
            return Optional.of(l);
        }
        Optional<CodeArchive> archive = host.store.archive(digest);
        if (archive.isEmpty()) {
            return Optional.empty();
        }
        synchronized (loaders) {
            l = loaders.get(digest);
            if (l == null) {
                l = new ArchiveClassLoader(archive.get(), CodeLoaders.class.getClassLoader());
                loaders.put(digest, l);
            }
        }
        return Optional.of(l);
    }

    /**
     * Takes an archive a peer sends (because a transfer of its asked for it), if its bytes hash to
     * the digest it claims and it is a jar.
     *
     * @param peer the peer
     * @param body the call's body, {@link Bodies#archive}
     * @return the reply
     */
    Reply onArchive(String peer, byte[] body) {
        Bodies.Archive sent;
        try {
            sent = Bodies.readArchive(body);
        } catch (IllegalArgumentException e) {
            return host.refuse("refused an archive from peer '" + peer + "': " + e.getMessage());
        }
        CodeArchive.Digest claimed = sent.claimed();
        CodeArchive archive = CodeArchive.of(sent.jar());
        if (!archive.digest().equals(claimed)) {
            return host.refuse("refused an archive from peer '" + peer + "': it claims " + claimed.hex() + " but its bytes hash to " + archive.digest().hex()
                    + " (tampered with or corrupted)");
        }
        try {
            ArchiveClassLoader checked = new ArchiveClassLoader(archive, CodeLoaders.class.getClassLoader());
            host.store.putArchive(archive);
            synchronized (loaders) {
                loaders.putIfAbsent(archive.digest(), checked); // the transfer that asked for it follows: no second read of the jar
            }
        } catch (IOException e) {
            return host.refuse("refused archive " + claimed + " from peer '" + peer + "': " + e.getMessage());
        }
        LOG.info("host {}: received archive {} ({} bytes) from peer '{}'", host.name, archive.digest(), sent.jar().length, peer);
        return Reply.ok();
    }
}
