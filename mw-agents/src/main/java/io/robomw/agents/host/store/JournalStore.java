package io.robomw.agents.host.store;

import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

import io.robomw.agents.host.code.CodeArchive;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.BufferedInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.nio.ByteBuffer;
import java.nio.channels.ClosedByInterruptException;
import java.nio.channels.FileChannel;
import java.nio.channels.FileLock;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.nio.file.StandardOpenOption;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.HexFormat;
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.zip.CRC32C;

/**
 * A durable {@link AgentStore}: an append-only journal in one directory, replayed when the host
 * starts again, and the archives of agent code beside it ({@code archives/<sha256>.jar}).
 *
 * <p>The journal begins with a header, then its records. All integers are big-endian.
 *
 * <pre>
 * header  [magic 0x89 'R' 'M' 'J' 4][format version 4]
 * record  [payload length 4][type 1][agent id 16][number 8]([data length 4][data])[CRC32C of the payload 4]
 *          \------------------------- payload -------------------------/
 * </pre>
 *
 * <table>
 * <caption>Record types ({@link RecordType}); the phase is the {@link AgentStore.Phase} the agent is in after it</caption>
 * <tr><th>code</th><th>type</th><th>number</th><th>data</th><th>forced</th><th>effect on replay</th></tr>
 * <tr><td>1</td><td>ACCEPTED</td><td>hop</td><td>the image</td><td>yes</td><td>the agent is held, phase ACCEPTED; the hop is seen</td></tr>
 * <tr><td>2</td><td>STARTED</td><td>hop</td><td>none</td><td>yes</td><td>phase STARTED (its stop's work had begun)</td></tr>
 * <tr><td>3</td><td>DEPARTING</td><td>the next hop</td><td>the image</td><td>no</td><td>phase DEPARTING, with the image it leaves with</td></tr>
 * <tr><td>4</td><td>DEPARTED</td><td>the hop it left with (versions 1 and 2: 0)</td><td>none</td><td>no</td><td>the copy that left with that
 *     hop (or, ending here, came with an earlier one) is no longer held: the agent is forgotten unless what is held of it came
 *     later (a hop to this same host stores the new copy before the old one is recorded departed); versions 1 and 2: the agent
 *     is no longer held</td></tr>
 * <tr><td>5</td><td>EVENT_PENDING</td><td>event seq</td><td>[owed since 8, ms since the epoch][the owed event] (version 1: the owed
 *     event alone, owed since the journal was opened)</td><td>yes</td><td>an event owed to its home</td></tr>
 * <tr><td>6</td><td>EVENT_DELIVERED</td><td>event seq</td><td>none</td><td>no</td><td>that event is no longer owed</td></tr>
 * <tr><td>7</td><td>SEEN</td><td>hop</td><td>none</td><td>no</td><td>the highest hop seen of the agent (compaction writes these)</td></tr>
 * <tr><td>8</td><td>EVENT_SEQ</td><td>next event seq</td><td>none</td><td>no</td><td>the number the held agent's next report or result takes
 *     (compaction writes these; version 2)</td></tr>
 * <tr><td>9</td><td>DEPARTING_SPOOLED</td><td>the next hop</td><td>[image length 4][CRC32C of the image 4]</td><td>no</td><td>as DEPARTING,
 *     with the image in the spool file {@code departing/<agent id>-<hop>}; if that file is missing, of another length or
 *     checksum (it is never forced: a power cut may lose it), the record is ignored and the agent resumes in its phase before
 *     (its stop begun: it goes on from the state it arrived with, its stop recorded as interrupted); version 4</td></tr>
 * </table>
 *
 * <p><b>A hop's state goes to the disk once.</b> An agent's image is written from the caller's
 * array (the transfer's own), and the store keeps no copy of it: it notes where the image is and
 * reads it back only to compact. The image an agent arrives with is in its ACCEPTED record,
 * forced. The image it leaves with is needed only if the host is killed before the next host
 * acknowledges it; images of {@value #SPOOL_MIN_BYTES} bytes or more are written to a spool file of
 * their own rather than into the journal, and the file is deleted once the next host has the
 * agent: the journal's {@code fdatasync}s never write it, and the page cache usually drops it
 * unwritten (a kill keeps it: the page cache survives the process). Smaller ones stay in the
 * journal, where they cost a few blocks.
 *
 * <p><b>Event numbers.</b> An agent's reports and results are numbered, and its home drops a number
 * it has seen. An agent held here carries in its image the next number as it was when it arrived;
 * the numbers of the events it owed since are in the EVENT_PENDING records (and, once the journal
 * is compacted, in an EVENT_SEQ record), so {@link #nextEventSeq} gives an agent resumed after a kill
 * the next number never used rather than the one it arrived with.
 *
 * <p><b>Format version.</b> The header is written when the journal is made (every open rewrites
 * the journal with what is live, header first), and checked when it is opened: a journal of a
 * version this store does not read (it reads 1 and {@value #FORMAT_VERSION}, and writes
 * {@value #FORMAT_VERSION}), or whose first bytes are neither the header nor a
 * record, is refused with an error naming the file, and so is a record of a type not in the
 * table. A journal written before the header existed (its records are those of version 1) is
 * recognised by a first record that reads as one (a known type and a good checksum), or by
 * nothing but the zeros ahead of where records would go, and is read as version 1 and rewritten
 * with the header, so the agents it holds are not lost.
 *
 * <p>A record cut short by a kill, or with a bad checksum, ends the replay there and is cut off.
 * Records that must survive a power cut (an accepted agent, a started stop, an owed result, an
 * archive) are forced to the disk ({@code fdatasync}) before the call returns; the others only
 * need to survive the process being killed, which the page cache does. A transferred agent's
 * ACCEPTED and STARTED records go in one write with one {@code fdatasync} ({@link #acceptedStarting}):
 * one per hop. The journal is rewritten with only what is live when it
 * grows past {@value #COMPACT_BYTES} bytes and four times what is live. One host per directory
 * (a file lock says so). Thread-safe.
 *
 * <p>The journal file is grown ahead of its records in zero-filled steps of
 * {@value #PREALLOCATE_BYTES} bytes, made durable once: a forced record then overwrites blocks the
 * file already has, so {@code fdatasync} writes its data without a file-system journal commit for
 * the file's new size (about 2x faster for records of some kilobytes on the project's machine).
 * Replay ends at the first zero length, where the zeros begin. Records larger than
 * {@value #PREALLOCATE_MAX_RECORD} bytes are appended past the zeros instead: their data costs
 * more than the commit they would save, and zero-filling ahead of them would double the writes.
 */
public final class JournalStore implements AgentStore {

    private static final Logger LOG = LoggerFactory.getLogger(JournalStore.class);
    private static final long COMPACT_BYTES = 32L << 20;
    /** How many agents' highest hops the store remembers. */
    static final int SEEN_CAPACITY = 100_000;
    private static final int MAX_RECORD = Integer.MAX_VALUE - 64;
    private static final int PREALLOCATE_BYTES = 4 << 20;
    private static final int PREALLOCATE_MAX_RECORD = 256 << 10;
    private static final ByteBuffer ZEROS = ByteBuffer.allocateDirect(1 << 20).asReadOnlyBuffer();

    /** The first four bytes of a journal: not a record length (negative), not text. */
    static final byte[] MAGIC = {(byte) 0x89, 'R', 'M', 'J'};
    /**
     * The format this store writes; version 2 added the EVENT_SEQ record, version 3 the hop in
     * DEPARTED records (before, a DEPARTED record forgot whatever copy of the agent was held),
     * version 4 the DEPARTING_SPOOLED record.
     */
    static final int FORMAT_VERSION = 4;
    /** The first version whose DEPARTED records carry the hop the agent left with. */
    static final int DEPARTED_HOP_VERSION = 3;
    /** The oldest format this store reads (its records are a subset of the current version's). */
    static final int OLDEST_READABLE_VERSION = 1;
    /** The first version with DEPARTING_SPOOLED records. */
    static final int SPOOL_VERSION = 4;
    /** Departing images of at least this many bytes go to a spool file rather than into the journal. */
    static final int SPOOL_MIN_BYTES = 64 * 1024;
    /** The header's length: magic and version. */
    static final int HEADER_LENGTH = 8;
    /** The shortest record payload: type, id, number. */
    private static final int MIN_PAYLOAD = 1 + 16 + 8;

    /** The kinds of records, each written as its {@link #code()} (the table is in the class javadoc). */
    enum RecordType implements WireCode {
        /** An agent accepted; its image. */
        ACCEPTED(1),
        /** Its stop's work begun. */
        STARTED(2),
        /** It is being sent on; its image after the stop. */
        DEPARTING(3),
        /** It is no longer here. */
        DEPARTED(4),
        /** An event owed to its home. */
        EVENT_PENDING(5),
        /** The home has that event. */
        EVENT_DELIVERED(6),
        /** The highest hop of it ever accepted. */
        SEEN(7),
        /** The next event number of an agent held here (from version 2). */
        EVENT_SEQ(8),
        /** It is being sent on; its image after the stop is in a spool file (from version 4). */
        DEPARTING_SPOOLED(9);

        private static final WireCodes<RecordType> CODES = WireCodes.of(RecordType.class, "record type");

        private final int code;

        RecordType(int code) {
            this.code = code;
        }

        /** @return the record type's code in the journal */
        @Override
        public int code() {
            return code;
        }

        /**
         * @param code a type byte as read (unsigned)
         * @return its record type
         * @throws IllegalArgumentException naming the code if no type has it
         */
        static RecordType fromCode(int code) {
            return CODES.get(code);
        }
    }

    private final Path dir;
    private final Path journal;
    private final Path archives;
    private final Path spool;
    private final FileChannel lockChannel;
    private final FileLock lock;
    private final Object writeLock = new Object();
    /** The agents held here: where each one's image is in the journal (not a copy of it). */
    private final Map<UUID, Held> live = new LinkedHashMap<>();
    /** The highest hop of each agent seen, for the last {@value #SEEN_CAPACITY} agents; read without the write lock. */
    private final Map<UUID, Long> seen = new ConcurrentHashMap<>();
    /** The agents of {@link #seen} in the order they were first seen, for forgetting the oldest; guarded by the write lock. */
    private final java.util.ArrayDeque<UUID> seenOrder = new java.util.ArrayDeque<>();
    private final int seenCapacity;
    /** The next event number of each agent held here that has owed an event since it arrived. */
    private final Map<UUID, Long> eventSeqs = new ConcurrentHashMap<>();
    private final Map<String, PendingEvent> events = new LinkedHashMap<>();
    private final Map<CodeArchive.Digest, CodeArchive> archiveCache = new ConcurrentHashMap<>();
    private final List<StoredAgent> recoveredAgents;
    private final List<PendingEvent> recoveredEvents;
    private FileChannel channel;
    /** Where the next record goes: the end of the records, before the zero-filled rest of the file. */
    private long end;
    /** The file's size, zero-filled from {@link #end} on. */
    private long allocated;
    private long liveBytes;
    /** How many times the journal was forced to the disk since it was opened (for tests); guarded by the write lock. */
    private long forces;
    /** The format version of the journal as it was read (its records are rewritten in {@link #FORMAT_VERSION}). */
    private int readVersion = FORMAT_VERSION;
    /** When the journal was opened: the owed-since of events a version 1 journal holds. */
    private final long openedAt = System.currentTimeMillis();

    private JournalStore(Path dir, int seenCapacity) throws IOException {
        this.dir = dir;
        this.seenCapacity = seenCapacity;
        this.journal = dir.resolve("journal");
        this.archives = dir.resolve("archives");
        this.spool = dir.resolve("departing");
        Files.createDirectories(archives);
        Files.createDirectories(spool);
        lockChannel = FileChannel.open(dir.resolve("lock"), StandardOpenOption.CREATE, StandardOpenOption.WRITE);
        FileLock l;
        try {
            l = lockChannel.tryLock();
        } catch (java.nio.channels.OverlappingFileLockException e) {
            l = null; // held by another store of this process
        }
        if (l == null) {
            lockChannel.close();
            throw new IOException("agent store " + dir + " is in use by another host (its lock file is held)");
        }
        this.lock = l;
        try {
            replay();
            recoveredAgents = live.values().stream().map(a -> new StoredAgent(a.id(), a.hop(), a.phase(), a.image())).toList();
            recoveredEvents = List.copyOf(events.values());
            compact();
            deleteUnheldSpoolFiles();
            deleteUnfinishedArchives(archives);
        } catch (IOException | RuntimeException e) {
            // A journal this store refuses must not keep the directory locked (a host retrying, or another, could not open it).
            try {
                if (channel != null) {
                    channel.close();
                }
            } finally {
                try {
                    lock.release();
                } finally {
                    lockChannel.close();
                }
            }
            throw e;
        }
    }

    /**
     * Opens (or creates) the store in a directory and replays its journal.
     *
     * @param dir the directory
     * @return the store, holding what the host had accepted before it stopped
     * @throws IOException if the directory cannot be used or another host holds it
     */
    public static JournalStore open(Path dir) throws IOException {
        return new JournalStore(dir, SEEN_CAPACITY);
    }

    /** {@link #open(Path)} remembering the hops of at most {@code seenCapacity} agents (for tests). */
    static JournalStore open(Path dir, int seenCapacity) throws IOException {
        return new JournalStore(dir, seenCapacity);
    }

    @Override
    public boolean durable() {
        return true;
    }

    /** @return the journal file */
    @Override
    public String location() {
        return journal.toString();
    }

    /** The image is written from the caller's array (no copy of it is made or kept: {@link #live} notes where it is in the journal). */
    @Override
    public void accepted(UUID id, long hop, byte[] from, int offset, int length) throws IOException {
        checkRange(from, offset, length);
        synchronized (writeLock) {
            long at = append(true, encode(RecordType.ACCEPTED, id, hop, from, offset, length));
            put(new Held(id, hop, Phase.ACCEPTED, at + DATA_OFFSET, length, null, null));
            see(id, hop);
        }
    }

    /**
     * One write and one {@code fdatasync} for both records (an ACCEPTED, then a STARTED record),
     * where {@link #accepted} and {@link #started} would take two of each; replayed, the agent is
     * in phase STARTED. The image is written from the caller's array.
     */
    @Override
    public void acceptedStarting(UUID id, long hop, byte[] from, int offset, int length) throws IOException {
        checkRange(from, offset, length);
        synchronized (writeLock) {
            ByteBuffer[] accepted = encode(RecordType.ACCEPTED, id, hop, from, offset, length);
            ByteBuffer[] started = encode(RecordType.STARTED, id, hop, null, 0, 0);
            ByteBuffer[] both = java.util.Arrays.copyOf(accepted, accepted.length + started.length);
            System.arraycopy(started, 0, both, accepted.length, started.length);
            long at = append(true, both);
            put(new Held(id, hop, Phase.STARTED, at + DATA_OFFSET, length, null, null));
            see(id, hop);
        }
    }

    @Override
    public void started(UUID id, long hop) throws IOException {
        synchronized (writeLock) {
            append(true, encode(RecordType.STARTED, id, hop, null, 0, 0));
            Held a = live.get(id);
            if (a != null) {
                live.put(id, a.in(hop, Phase.STARTED));
            }
        }
    }

    /**
     * The image is written from the caller's array (no copy of it is made or kept); one of
     * {@value #SPOOL_MIN_BYTES} bytes or more to a spool file, with a DEPARTING_SPOOLED record.
     */
    @Override
    public void departing(UUID id, long hop, byte[] from, int offset, int length) throws IOException {
        checkRange(from, offset, length);
        if (length >= SPOOL_MIN_BYTES) {
            Path file = spoolFile(id, hop);
            try (FileChannel c = FileChannel.open(file, StandardOpenOption.CREATE, StandardOpenOption.WRITE, StandardOpenOption.TRUNCATE_EXISTING)) {
                ByteBuffer b = ByteBuffer.wrap(from, offset, length);
                while (b.hasRemaining()) {
                    c.write(b);
                }
            }
            CRC32C crc = new CRC32C();
            crc.update(from, offset, length);
            byte[] data = ByteBuffer.allocate(8).putInt(length).putInt((int) crc.getValue()).array();
            synchronized (writeLock) {
                append(false, encode(RecordType.DEPARTING_SPOOLED, id, hop, data, 0, data.length));
                put(new Held(id, hop, Phase.DEPARTING, -1, length, null, file));
            }
            return;
        }
        synchronized (writeLock) {
            long at = append(false, encode(RecordType.DEPARTING, id, hop, from, offset, length));
            put(new Held(id, hop, Phase.DEPARTING, at + DATA_OFFSET, length, null, null));
        }
    }

    private Path spoolFile(UUID id, long hop) {
        return spool.resolve(id + "-" + hop);
    }

    private static void checkRange(byte[] from, int offset, int length) {
        java.util.Objects.checkFromIndexSize(offset, length, from.length);
        if (length > MAX_RECORD - MIN_PAYLOAD - 4) {
            throw new IllegalArgumentException("an image of " + length + " bytes is too large for a journal record");
        }
    }

    @Override
    public void departed(UUID id, long hop) throws IOException {
        synchronized (writeLock) {
            append(false, encode(RecordType.DEPARTED, id, hop, null, 0, 0));
            forget(id, hop);
            maybeCompact();
        }
    }

    /**
     * Forgets an agent whose copy that left with {@code hop} is gone, unless what is held of it came
     * with that hop or a later one: the agent came back, or hopped to this same host, whose
     * ACCEPTED record is written before the sender records the old copy departed.
     */
    private void forget(UUID id, long hop) {
        Held held = live.get(id);
        if (held == null || held.hop() < hop || held.hop() == hop && held.phase() == Phase.DEPARTING) {
            remove(id);
            eventSeqs.remove(id);
        }
    }

    @Override
    public long highestHop(UUID id) {
        return seen.getOrDefault(id, -1L);
    }

    @Override
    public long nextEventSeq(UUID id) {
        return eventSeqs.getOrDefault(id, 0L);
    }

    @Override
    public void eventPending(PendingEvent event) throws IOException {
        synchronized (writeLock) {
            byte[] data = pendingData(event);
            append(true, encode(RecordType.EVENT_PENDING, event.id(), event.seq(), data, 0, data.length));
            if (live.containsKey(event.id())) {
                eventSeqs.merge(event.id(), event.seq() + 1, Math::max);
            }
            events.put(key(event.id(), event.seq()), event);
            liveBytes += event.event().length;
        }
    }

    @Override
    public void eventDelivered(UUID id, long seq) throws IOException {
        synchronized (writeLock) {
            append(false, encode(RecordType.EVENT_DELIVERED, id, seq, null, 0, 0));
            PendingEvent e = events.remove(key(id, seq));
            if (e != null) {
                liveBytes -= e.event().length;
            }
            maybeCompact();
        }
    }

    /** Deletes the archives a killed process was writing (their {@code .jar} was never moved into place). */
    private static void deleteUnfinishedArchives(Path archives) throws IOException {
        try (var unfinished = Files.newDirectoryStream(archives, "*.tmp")) {
            for (Path p : unfinished) {
                Files.deleteIfExists(p);
            }
        }
    }

    @Override
    public void putArchive(CodeArchive archive) throws IOException {
        Path file = archives.resolve(archive.digest().hex() + ".jar");
        if (!Files.exists(file)) {
            // A file of its own for each writer: two agents of the same code may bring its archive at once.
            Path tmp = Files.createTempFile(archives, archive.digest().hex() + "-", ".tmp");
            try {
                try (FileChannel c = FileChannel.open(tmp, StandardOpenOption.WRITE, StandardOpenOption.TRUNCATE_EXISTING)) {
                    ByteBuffer b = ByteBuffer.wrap(archive.bytes());
                    while (b.hasRemaining()) {
                        c.write(b);
                    }
                    c.force(true);
                }
                Files.move(tmp, file, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
            } finally {
                Files.deleteIfExists(tmp);
            }
        }
        archiveCache.putIfAbsent(archive.digest(), archive);
    }

    @Override
    public Optional<CodeArchive> archive(CodeArchive.Digest digest) {
        CodeArchive a = archiveCache.get(digest);
        if (a != null) {
            return Optional.of(a);
        }
        Path file = archives.resolve(digest.hex() + ".jar");
        if (!Files.exists(file)) {
            return Optional.empty();
        }
        try {
            CodeArchive read = CodeArchive.of(Files.readAllBytes(file));
            if (!read.digest().equals(digest)) {
                LOG.warn("archive {} in {} does not match its digest; ignoring it", digest, archives);
                return Optional.empty();
            }
            archiveCache.putIfAbsent(digest, read);
            return Optional.of(read);
        } catch (IOException e) {
            LOG.warn("cannot read archive {}: {}", file, e.toString());
            return Optional.empty();
        }
    }

    /** @return how many times records were forced to the disk since the store was opened (not counting its own growth and compaction) */
    long forces() {
        synchronized (writeLock) {
            return forces;
        }
    }

    @Override
    public List<StoredAgent> recoveredAgents() {
        return recoveredAgents;
    }

    @Override
    public List<PendingEvent> recoveredEvents() {
        return recoveredEvents;
    }

    @Override
    public void close() throws IOException {
        synchronized (writeLock) {
            try {
                if (channel != null) {
                    uninterrupted(() -> channel.truncate(end)); // no zeros left behind
                    channel.close();
                }
            } finally {
                try {
                    lock.release();
                } finally {
                    lockChannel.close(); // the directory is free for the next host even if the journal could not be tidied
                }
            }
        }
    }

    /** A write to the journal. */
    private interface JournalIo {
        void run() throws IOException;
    }

    /**
     * Runs a write to the journal so that a thread's interrupt does not break the store: a
     * {@link FileChannel} closes itself when a thread blocked in it is interrupted, which would
     * fail every later write of every thread. The interrupt status is cleared for the write and
     * set again after it; an interrupt that arrives during the write closes the channel, which is
     * opened again and the write (to the same position, so it is the same bytes) done once more.
     */
    private void uninterrupted(JournalIo io) throws IOException {
        boolean interrupted = Thread.interrupted();
        try {
            try {
                io.run();
            } catch (ClosedByInterruptException e) {
                interrupted |= Thread.interrupted();
                channel = FileChannel.open(journal, StandardOpenOption.READ, StandardOpenOption.WRITE);
                io.run();
            }
        } finally {
            if (interrupted) {
                Thread.currentThread().interrupt();
            }
        }
    }

    // ---- journal ----

    private void put(Held a) {
        Held old = live.put(a.id(), a);
        if (old != null) {
            liveBytes -= old.length();
            unspool(old, a);
        }
        liveBytes += a.length();
    }

    private void remove(UUID id) {
        Held old = live.remove(id);
        if (old != null) {
            liveBytes -= old.length();
            unspool(old, null);
        }
    }

    /** Deletes the spool file of a copy no longer held (unless the copy that replaces it is in that same file). */
    private void unspool(Held old, Held now) {
        if (old.spooled() != null && (now == null || !old.spooled().equals(now.spooled()))) {
            try {
                Files.deleteIfExists(old.spooled());
            } catch (IOException e) {
                LOG.warn("agent store {}: cannot delete the spool file {} of an agent no longer held: {}", dir, old.spooled(), e.toString());
            }
        }
    }

    /** After opening: deletes spool files of copies no longer held (a kill between a departure and the deletion leaves them). */
    private void deleteUnheldSpoolFiles() throws IOException {
        java.util.Set<Path> held = new java.util.HashSet<>();
        live.values().forEach(a -> {
            if (a.spooled() != null) {
                held.add(a.spooled());
            }
        });
        try (java.util.stream.Stream<Path> files = Files.list(spool)) {
            for (Path f : (Iterable<Path>) files::iterator) {
                if (!held.contains(f)) {
                    Files.deleteIfExists(f);
                }
            }
        }
    }

    /**
     * An agent held here, as the journal has it: its image is {@code length} bytes at
     * {@code dataAt} in the journal file, and also in {@code image} while the replay's copy is
     * kept (from a journal's opening to its first compaction), else {@code null}; or, spooled,
     * in the file {@code spooled} ({@code dataAt} -1).
     */
    private record Held(UUID id, long hop, Phase phase, long dataAt, int length, byte[] image, Path spooled) {
        Held in(long newHop, Phase newPhase) {
            return new Held(id, newHop, newPhase, dataAt, length, image, spooled);
        }
    }

    /** @return a held agent's image, read back from the journal unless the replay's copy is kept */
    private byte[] imageOf(Held a) throws IOException {
        if (a.image() != null) {
            return a.image();
        }
        if (a.spooled() != null) {
            byte[] b = Files.readAllBytes(a.spooled());
            if (b.length != a.length()) {
                throw new IOException("agent store spool file " + a.spooled() + " holds " + b.length + " bytes, not the " + a.length() + " of agent "
                        + a.id() + "'s image");
            }
            return b;
        }
        ByteBuffer b = ByteBuffer.allocate(a.length());
        long at = a.dataAt();
        while (b.hasRemaining()) {
            int n = channel.read(b, at);
            if (n < 0) {
                throw new IOException("agent store journal " + journal + " ends inside the image of agent " + a.id() + " (at byte " + a.dataAt() + ")");
            }
            at += n;
        }
        return b.array();
    }

    /** @return an EVENT_PENDING record's data: when it was first owed, then the event */
    private static byte[] pendingData(PendingEvent e) {
        return ByteBuffer.allocate(8 + e.event().length).putLong(e.owedSince()).put(e.event()).array();
    }

    /**
     * Remembers an agent's highest hop, forgetting the agent first seen longest ago beyond
     * {@value #SEEN_CAPACITY} agents (as {@link MemoryStore} does), so a host that sees agents for
     * days keeps a bounded map and journal. Only a transfer of an old hop of a forgotten agent could
     * then be taken again, and a sender resends a hop only until it is acknowledged. Called with
     * the write lock held (or during replay).
     */
    private void see(UUID id, long hop) {
        if (seen.put(id, Math.max(hop, seen.getOrDefault(id, hop))) == null) {
            seenOrder.addLast(id); // first seen now
        }
        for (int tries = seenOrder.size(); seen.size() > seenCapacity && tries > 0; tries--) {
            UUID oldest = seenOrder.pollFirst();
            if (live.containsKey(oldest)) {
                seenOrder.addLast(oldest); // still held here: keep it
            } else {
                seen.remove(oldest);
            }
        }
    }

    private static String key(UUID id, long seq) {
        return id + "/" + seq;
    }

    /**
     * Writes records (one write of all their parts, at the end of the records) and, if
     * {@code force}, makes them durable with one {@code fdatasync}.
     *
     * @return where the first record starts in the journal
     */
    private long append(boolean force, ByteBuffer... parts) throws IOException {
        long total = 0;
        for (ByteBuffer p : parts) {
            total += p.remaining();
        }
        long length = total;
        if (length <= PREALLOCATE_MAX_RECORD && end + length > allocated) {
            long size = end + length + PREALLOCATE_BYTES;
            uninterrupted(() -> preallocate(size));
        }
        long start = end;
        uninterrupted(() -> {
            ByteBuffer[] b = new ByteBuffer[parts.length];
            for (int i = 0; i < parts.length; i++) {
                b[i] = parts[i].duplicate();
            }
            channel.position(start);
            long written = 0;
            while (written < length) {
                written += channel.write(b);
            }
            if (force) {
                channel.force(false);
            }
        });
        if (force) {
            forces++;
        }
        end = start + length;
        allocated = Math.max(allocated, end);
        return start;
    }

    /** Zero-fills the file up to {@code size} and makes that durable (size and blocks), once per step. */
    private void preallocate(long size) throws IOException {
        long at = allocated;
        while (at < size) {
            ByteBuffer z = ZEROS.duplicate();
            z.limit((int) Math.min(z.capacity(), size - at));
            while (z.hasRemaining()) {
                at += channel.write(z, at);
            }
        }
        channel.force(true);
        allocated = at;
    }

    /** Where a record's data starts, from the record's start: length, type, id, number, data length. */
    private static final int DATA_OFFSET = 4 + MIN_PAYLOAD + 4;

    /**
     * A record as the parts to write: its head, its data (the caller's array, not copied) and its
     * checksum, computed over the head's payload part and the data in place.
     *
     * @param data the data, or {@code null} for a record without
     */
    private static ByteBuffer[] encode(RecordType type, UUID id, long number, byte[] data, int off, int len) {
        int payload = MIN_PAYLOAD + (data == null ? 0 : 4 + len);
        ByteBuffer head = ByteBuffer.allocate(data == null ? 4 + MIN_PAYLOAD : DATA_OFFSET);
        head.putInt(payload).put((byte) type.code()).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).putLong(number);
        if (data != null) {
            head.putInt(len);
        }
        CRC32C crc = new CRC32C();
        crc.update(head.array(), 4, head.position() - 4);
        if (data != null) {
            crc.update(data, off, len);
        }
        ByteBuffer tail = ByteBuffer.allocate(4).putInt((int) crc.getValue()).flip();
        head.flip();
        return data == null ? new ByteBuffer[] {head, tail} : new ByteBuffer[] {head, ByteBuffer.wrap(data, off, len), tail};
    }

    /**
     * Reads the journal's header and replays its records into the maps.
     *
     * @throws IOException naming the file if its header is missing or of another version, or a record is of an unknown type or malformed
     */
    private void replay() throws IOException {
        long good = 0;
        if (Files.exists(journal)) {
            long size = Files.size(journal);
            try (InputStream raw = Files.newInputStream(journal); DataInputStream in = new DataInputStream(new BufferedInputStream(raw, 1 << 16))) {
                good = readHeader(in, size);
                while (true) {
                    int payload;
                    try {
                        payload = in.readInt();
                    } catch (EOFException end) {
                        break;
                    }
                    if (payload == 0) {
                        break; // the zero-filled space ahead of the records
                    }
                    if (payload < MIN_PAYLOAD || payload > MAX_RECORD) {
                        LOG.warn("agent store {}: bad record length {} at byte {}; the journal is cut off there", dir, payload, good);
                        break;
                    }
                    if (good + 4 + payload + 4 > size) {
                        LOG.warn("agent store {}: the last record (at byte {}) was cut short, as a kill leaves it; dropped", dir, good);
                        break;
                    }
                    byte[] body = new byte[payload];
                    int crcValue;
                    try {
                        in.readFully(body);
                        crcValue = in.readInt();
                    } catch (EOFException torn) {
                        LOG.warn("agent store {}: the last record (at byte {}) was cut short, as a kill leaves it; dropped", dir, good);
                        break;
                    }
                    CRC32C crc = new CRC32C();
                    crc.update(body);
                    if ((int) crc.getValue() != crcValue) {
                        LOG.warn("agent store {}: record at byte {} has a bad checksum; the journal is cut off there", dir, good);
                        break;
                    }
                    apply(ByteBuffer.wrap(body), good);
                    good += 4 + payload + 4;
                }
            }
        }
        channel = FileChannel.open(journal, StandardOpenOption.CREATE, StandardOpenOption.READ, StandardOpenOption.WRITE);
        channel.truncate(good);
        end = good;
        allocated = good;
    }

    /**
     * Checks the journal's header.
     *
     * @return where the records start: after the header, or at 0 in a journal written before the header existed
     * @throws IOException naming the file if the header is of another version, or the journal has neither a header nor a first record
     */
    private long readHeader(DataInputStream in, long size) throws IOException {
        in.mark(HEADER_LENGTH);
        byte[] head = in.readNBytes(HEADER_LENGTH);
        if (head.length == 0) {
            return 0; // empty
        }
        if (head.length >= MAGIC.length && java.util.Arrays.equals(head, 0, MAGIC.length, MAGIC, 0, MAGIC.length)) {
            if (head.length < HEADER_LENGTH) {
                throw new IOException("agent store journal " + journal + " is cut short inside its header (" + head.length + " bytes)");
            }
            int version = ByteBuffer.wrap(head, MAGIC.length, 4).getInt();
            if (version < OLDEST_READABLE_VERSION || version > FORMAT_VERSION) {
                throw new IOException("agent store journal " + journal + " has format version " + version + "; this RoboMW reads versions "
                        + OLDEST_READABLE_VERSION + " to " + FORMAT_VERSION + " (start the host with the RoboMW that wrote it until its agents have left, or move the journal away)");
            }
            readVersion = version;
            if (version < FORMAT_VERSION) {
                LOG.info("agent store {}: the journal has format version {}; rewriting it as version {}", dir, version, FORMAT_VERSION);
            }
            return HEADER_LENGTH;
        }
        in.reset();
        if (!headerless(in, size)) {
            throw new IOException("agent store journal " + journal + " has no format header (it begins with 0x" + HexFormat.of().formatHex(head)
                    + "): it is not a RoboMW agent journal, or one damaged at its start; move it away to start the host with an empty store");
        }
        readVersion = 1;
        LOG.info("agent store {}: the journal has no format header (written before RoboMW gave it one); reading it as version 1 and rewriting it as"
                + " version {}", dir, FORMAT_VERSION);
        return 0;
    }

    /**
     * @return whether the journal reads as one written before the header existed: nothing but the
     *         zeros ahead of records, or a first record of a known type with a good checksum (the
     *         stream is left at its start)
     */
    private static boolean headerless(DataInputStream in, long size) throws IOException {
        in.mark(Integer.MAX_VALUE); // the buffer grows only as far as the first record
        try {
            int payload = in.readInt();
            if (payload == 0) {
                return true;
            }
            if (payload < MIN_PAYLOAD || 4L + payload + 4 > size) {
                return false;
            }
            byte[] body = new byte[payload];
            in.readFully(body);
            int crcValue = in.readInt();
            CRC32C crc = new CRC32C();
            crc.update(body);
            RecordType.fromCode(body[0] & 0xFF);
            return (int) crc.getValue() == crcValue;
        } catch (EOFException | IllegalArgumentException e) {
            return false;
        } finally {
            in.reset();
        }
    }

    /**
     * Applies one record's payload (its checksum already checked).
     *
     * @param at where the record starts in the journal, for errors
     * @throws IOException naming the file and the offset if its type is unknown or its data is malformed
     */
    private void apply(ByteBuffer b, long at) throws IOException {
        int code = b.get() & 0xFF;
        RecordType type;
        try {
            type = RecordType.fromCode(code);
        } catch (IllegalArgumentException e) {
            throw new IOException("agent store journal " + journal + ": the record at byte " + at + " has an " + e.getMessage()
                    + "; it was written by another RoboMW (start the host with the RoboMW that wrote it, or move the journal away)");
        }
        UUID id = new UUID(b.getLong(), b.getLong());
        long number = b.getLong();
        byte[] data = null;
        if (b.remaining() > 0) {
            int length = b.remaining() >= 4 ? b.getInt() : -1;
            if (length != b.remaining()) {
                throw new IOException("agent store journal " + journal + ": the " + type + " record at byte " + at + " declares " + length
                        + " bytes of data but holds " + b.remaining());
            }
            data = new byte[length];
            b.get(data);
        }
        boolean needsData = type == RecordType.ACCEPTED || type == RecordType.DEPARTING || type == RecordType.EVENT_PENDING
                || type == RecordType.DEPARTING_SPOOLED;
        if (needsData != (data != null)) {
            throw new IOException("agent store journal " + journal + ": the " + type + " record at byte " + at + (needsData ? " has no data" : " has data it should not have"));
        }
        switch (type) {
            case ACCEPTED -> {
                put(new Held(id, number, Phase.ACCEPTED, at + DATA_OFFSET, data.length, data, null));
                see(id, number);
            }
            case STARTED -> {
                Held a = live.get(id);
                if (a != null) {
                    live.put(id, a.in(number, Phase.STARTED));
                }
            }
            case DEPARTING -> put(new Held(id, number, Phase.DEPARTING, at + DATA_OFFSET, data.length, data, null));
            case DEPARTING_SPOOLED -> replaySpooled(id, number, data, at);
            case DEPARTED -> {
                if (readVersion >= DEPARTED_HOP_VERSION) {
                    forget(id, number);
                } else {
                    remove(id);
                    eventSeqs.remove(id);
                }
            }
            case EVENT_PENDING -> {
                long since = openedAt;
                if (readVersion >= 2) {
                    if (data.length < 8) {
                        throw new IOException("agent store journal " + journal + ": the EVENT_PENDING record at byte " + at + " holds " + data.length
                                + " bytes, fewer than its 8-byte owed-since time");
                    }
                    since = ByteBuffer.wrap(data).getLong();
                    data = java.util.Arrays.copyOfRange(data, 8, data.length);
                }
                events.put(key(id, number), new PendingEvent(id, number, since, data));
                liveBytes += data.length;
                if (live.containsKey(id)) {
                    eventSeqs.merge(id, number + 1, Math::max);
                }
            }
            case EVENT_DELIVERED -> {
                PendingEvent e = events.remove(key(id, number));
                if (e != null) {
                    liveBytes -= e.event().length;
                }
            }
            case SEEN -> see(id, number);
            case EVENT_SEQ -> eventSeqs.merge(id, number, Math::max);
        }
    }

    /**
     * A DEPARTING_SPOOLED record: the agent is departing with the image in its spool file, if the
     * file is there, whole and right; else the record is ignored (the file is never forced).
     */
    private void replaySpooled(UUID id, long hop, byte[] data, long at) throws IOException {
        if (data.length != 8) {
            throw new IOException("agent store journal " + journal + ": the DEPARTING_SPOOLED record at byte " + at + " holds " + data.length
                    + " bytes of data, not 8 (length and checksum)");
        }
        ByteBuffer d = ByteBuffer.wrap(data);
        int length = d.getInt();
        int crcValue = d.getInt();
        Path file = spoolFile(id, hop);
        byte[] image = null;
        if (Files.exists(file) && Files.size(file) == length) {
            image = Files.readAllBytes(file);
            CRC32C crc = new CRC32C();
            crc.update(image);
            if ((int) crc.getValue() != crcValue) {
                image = null;
            }
        }
        if (image == null) {
            LOG.warn("agent store {}: agent {} was departing with hop {}, but its spool file {} is missing or damaged (it is not forced: a power cut"
                    + " loses it); it resumes from the state it arrived with", dir, id, hop, file);
            return;
        }
        put(new Held(id, hop, Phase.DEPARTING, -1, length, image, file));
    }

    private void maybeCompact() throws IOException {
        long size = end;
        if (size > COMPACT_BYTES && size > 4 * Math.max(liveBytes, 1)) {
            uninterrupted(this::compact);
        }
    }

    /**
     * Rewrites the journal with only what is live; atomically replaces the old one. The images of
     * the agents held are read back from the old journal (or taken from the replay's copies), and
     * {@link #live} then notes where they are in the new one.
     */
    private void compact() throws IOException {
        synchronized (writeLock) {
            Path fresh = dir.resolve("journal.new");
            Map<UUID, Held> moved = new LinkedHashMap<>();
            try (FileChannel out = FileChannel.open(fresh, StandardOpenOption.CREATE, StandardOpenOption.WRITE, StandardOpenOption.TRUNCATE_EXISTING)) {
                List<ByteBuffer> records = new ArrayList<>();
                records.add(ByteBuffer.allocate(HEADER_LENGTH).put(MAGIC).putInt(FORMAT_VERSION).flip());
                long[] at = {HEADER_LENGTH};
                java.util.function.Consumer<ByteBuffer[]> add = parts -> {
                    for (ByteBuffer b : parts) {
                        records.add(b);
                        at[0] += b.remaining();
                    }
                };
                seen.forEach((id, hop) -> add.accept(encode(RecordType.SEEN, id, hop, null, 0, 0)));
                for (Held a : live.values()) {
                    byte[] image = imageOf(a);
                    RecordType type = a.phase() == Phase.DEPARTING ? RecordType.DEPARTING : RecordType.ACCEPTED;
                    moved.put(a.id(), new Held(a.id(), a.hop(), a.phase(), at[0] + DATA_OFFSET, image.length, null, null));
                    add.accept(encode(type, a.id(), a.hop(), image, 0, image.length));
                    if (a.phase() == Phase.STARTED) {
                        add.accept(encode(RecordType.STARTED, a.id(), a.hop(), null, 0, 0));
                    }
                }
                eventSeqs.forEach((id, next) -> {
                    if (live.containsKey(id)) {
                        add.accept(encode(RecordType.EVENT_SEQ, id, next, null, 0, 0));
                    }
                });
                for (PendingEvent e : events.values()) {
                    byte[] data = pendingData(e);
                    add.accept(encode(RecordType.EVENT_PENDING, e.id(), e.seq(), data, 0, data.length));
                }
                for (ByteBuffer r : records) {
                    while (r.hasRemaining()) {
                        out.write(r);
                    }
                }
                out.force(true);
            }
            if (channel != null) {
                channel.close();
            }
            Files.move(fresh, journal, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
            channel = FileChannel.open(journal, StandardOpenOption.READ, StandardOpenOption.WRITE);
            end = channel.size();
            allocated = end;
            // Spooled images are in the compacted journal now (DEPARTING records): their files go.
            for (Held a : live.values()) {
                unspool(a, null);
            }
            live.putAll(moved);
        }
    }
}
