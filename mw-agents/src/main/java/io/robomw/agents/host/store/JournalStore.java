package io.robomw.agents.host.store;

import io.robomw.agents.host.code.CodeArchive;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.BufferedInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.nio.ByteBuffer;
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
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.ConcurrentHashMap;
import java.util.zip.CRC32C;

/**
 * A durable {@link AgentStore}: an append-only journal in one directory, replayed when the host
 * starts again, and the archives of agent code beside it ({@code archives/<sha256>.jar}).
 *
 * <p>Each record is {@code [length][type][payload][CRC32C]}; a record cut short by a kill, or
 * with a bad checksum, ends the replay there and is cut off. Records that must survive a power
 * cut (an accepted agent, a started stop, an owed result, an archive) are forced to the disk
 * ({@code fdatasync}) before the call returns; the others only need to survive the process being
 * killed, which the page cache does. The journal is rewritten with only what is live when it
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
    private static final int MAX_RECORD = Integer.MAX_VALUE - 64;
    private static final int PREALLOCATE_BYTES = 4 << 20;
    private static final int PREALLOCATE_MAX_RECORD = 256 << 10;
    private static final ByteBuffer ZEROS = ByteBuffer.allocateDirect(1 << 20).asReadOnlyBuffer();

    private static final byte ACCEPTED = 1;
    private static final byte STARTED = 2;
    private static final byte DEPARTING = 3;
    private static final byte DEPARTED = 4;
    private static final byte EVENT_PENDING = 5;
    private static final byte EVENT_DELIVERED = 6;
    private static final byte SEEN = 7;

    private final Path dir;
    private final Path journal;
    private final Path archives;
    private final FileChannel lockChannel;
    private final FileLock lock;
    private final Object writeLock = new Object();
    private final Map<UUID, StoredAgent> live = new LinkedHashMap<>();
    private final Map<UUID, Long> seen = new ConcurrentHashMap<>();
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

    private JournalStore(Path dir) throws IOException {
        this.dir = dir;
        this.journal = dir.resolve("journal");
        this.archives = dir.resolve("archives");
        Files.createDirectories(archives);
        lockChannel = FileChannel.open(dir.resolve("lock"), StandardOpenOption.CREATE, StandardOpenOption.WRITE);
        FileLock l = lockChannel.tryLock();
        if (l == null) {
            lockChannel.close();
            throw new IOException("agent store " + dir + " is in use by another host (its lock file is held)");
        }
        this.lock = l;
        replay();
        recoveredAgents = List.copyOf(live.values());
        recoveredEvents = List.copyOf(events.values());
        compact();
    }

    /**
     * Opens (or creates) the store in a directory and replays its journal.
     *
     * @param dir the directory
     * @return the store, holding what the host had accepted before it stopped
     * @throws IOException if the directory cannot be used or another host holds it
     */
    public static JournalStore open(Path dir) throws IOException {
        return new JournalStore(dir);
    }

    @Override
    public boolean durable() {
        return true;
    }

    @Override
    public void accepted(UUID id, long hop, byte[] from, int offset, int length) throws IOException {
        byte[] image = java.util.Arrays.copyOfRange(from, offset, offset + length);
        synchronized (writeLock) {
            append(ACCEPTED, id, hop, image, true);
            put(new StoredAgent(id, hop, Phase.ACCEPTED, image));
            seen.merge(id, hop, Math::max);
        }
    }

    @Override
    public void started(UUID id, long hop) throws IOException {
        synchronized (writeLock) {
            append(STARTED, id, hop, null, true);
            StoredAgent a = live.get(id);
            if (a != null) {
                live.put(id, new StoredAgent(id, hop, Phase.STARTED, a.image()));
            }
        }
    }

    @Override
    public void departing(UUID id, long hop, byte[] from, int offset, int length) throws IOException {
        byte[] image = java.util.Arrays.copyOfRange(from, offset, offset + length);
        synchronized (writeLock) {
            append(DEPARTING, id, hop, image, false);
            put(new StoredAgent(id, hop, Phase.DEPARTING, image));
        }
    }

    @Override
    public void departed(UUID id) throws IOException {
        synchronized (writeLock) {
            append(DEPARTED, id, 0, null, false);
            remove(id);
            maybeCompact();
        }
    }

    @Override
    public long highestHop(UUID id) {
        return seen.getOrDefault(id, -1L);
    }

    @Override
    public void eventPending(PendingEvent event) throws IOException {
        synchronized (writeLock) {
            append(EVENT_PENDING, event.id(), event.seq(), event.event(), true);
            events.put(key(event.id(), event.seq()), event);
            liveBytes += event.event().length;
        }
    }

    @Override
    public void eventDelivered(UUID id, long seq) throws IOException {
        synchronized (writeLock) {
            append(EVENT_DELIVERED, id, seq, null, false);
            PendingEvent e = events.remove(key(id, seq));
            if (e != null) {
                liveBytes -= e.event().length;
            }
            maybeCompact();
        }
    }

    @Override
    public void putArchive(CodeArchive archive) throws IOException {
        Path file = archives.resolve(archive.digest().hex() + ".jar");
        if (!Files.exists(file)) {
            Path tmp = archives.resolve(archive.digest().hex() + ".tmp");
            try (FileChannel c = FileChannel.open(tmp, StandardOpenOption.CREATE, StandardOpenOption.WRITE, StandardOpenOption.TRUNCATE_EXISTING)) {
                ByteBuffer b = ByteBuffer.wrap(archive.bytes());
                while (b.hasRemaining()) {
                    c.write(b);
                }
                c.force(true);
            }
            Files.move(tmp, file, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
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
            if (channel != null) {
                channel.truncate(end); // no zeros left behind
                channel.close();
            }
            lock.release();
            lockChannel.close();
        }
    }

    // ---- journal ----

    private void put(StoredAgent a) {
        StoredAgent old = live.put(a.id(), a);
        if (old != null) {
            liveBytes -= old.image().length;
        }
        liveBytes += a.image().length;
    }

    private void remove(UUID id) {
        StoredAgent old = live.remove(id);
        if (old != null) {
            liveBytes -= old.image().length;
        }
    }

    private static String key(UUID id, long seq) {
        return id + "/" + seq;
    }

    private void append(byte type, UUID id, long number, byte[] data, boolean force) throws IOException {
        ByteBuffer b = encode(type, id, number, data);
        int length = b.remaining();
        if (length <= PREALLOCATE_MAX_RECORD && end + length > allocated) {
            preallocate(end + length + PREALLOCATE_BYTES);
        }
        long at = end;
        while (b.hasRemaining()) {
            at += channel.write(b, at);
        }
        end = at;
        allocated = Math.max(allocated, end);
        if (force) {
            channel.force(false);
        }
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

    private static ByteBuffer encode(byte type, UUID id, long number, byte[] data) {
        int payload = 1 + 16 + 8 + (data == null ? 0 : 4 + data.length);
        ByteBuffer b = ByteBuffer.allocate(4 + payload + 4);
        b.putInt(payload).put(type).putLong(id.getMostSignificantBits()).putLong(id.getLeastSignificantBits()).putLong(number);
        if (data != null) {
            b.putInt(data.length).put(data);
        }
        CRC32C crc = new CRC32C();
        crc.update(b.array(), 4, payload);
        b.putInt((int) crc.getValue());
        return b.flip();
    }

    private void replay() throws IOException {
        long good = 0;
        if (Files.exists(journal)) {
            try (InputStream raw = Files.newInputStream(journal); DataInputStream in = new DataInputStream(new BufferedInputStream(raw, 1 << 16))) {
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
                    if (payload < 25 || payload > MAX_RECORD) {
                        LOG.warn("agent store {}: bad record length {} at byte {}; the journal is cut off there", dir, payload, good);
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
                    apply(ByteBuffer.wrap(body));
                    good += 4 + payload + 4;
                }
            }
        }
        channel = FileChannel.open(journal, StandardOpenOption.CREATE, StandardOpenOption.WRITE);
        channel.truncate(good);
        end = good;
        allocated = good;
    }

    private void apply(ByteBuffer b) {
        byte type = b.get();
        UUID id = new UUID(b.getLong(), b.getLong());
        long number = b.getLong();
        byte[] data = null;
        if (b.remaining() >= 4) {
            data = new byte[b.getInt()];
            b.get(data);
        }
        switch (type) {
            case ACCEPTED -> {
                put(new StoredAgent(id, number, Phase.ACCEPTED, data));
                seen.merge(id, number, Math::max);
            }
            case STARTED -> {
                StoredAgent a = live.get(id);
                if (a != null) {
                    live.put(id, new StoredAgent(id, number, Phase.STARTED, a.image()));
                }
            }
            case DEPARTING -> put(new StoredAgent(id, number, Phase.DEPARTING, data));
            case DEPARTED -> remove(id);
            case EVENT_PENDING -> {
                events.put(key(id, number), new PendingEvent(id, number, data));
                liveBytes += data.length;
            }
            case EVENT_DELIVERED -> {
                PendingEvent e = events.remove(key(id, number));
                if (e != null) {
                    liveBytes -= e.event().length;
                }
            }
            case SEEN -> seen.merge(id, number, Math::max);
            default -> LOG.warn("agent store {}: unknown record type {} ignored", dir, type);
        }
    }

    private void maybeCompact() throws IOException {
        long size = end;
        if (size > COMPACT_BYTES && size > 4 * Math.max(liveBytes, 1)) {
            compact();
        }
    }

    /** Rewrites the journal with only what is live; atomically replaces the old one. */
    private void compact() throws IOException {
        synchronized (writeLock) {
            Path fresh = dir.resolve("journal.new");
            try (FileChannel out = FileChannel.open(fresh, StandardOpenOption.CREATE, StandardOpenOption.WRITE, StandardOpenOption.TRUNCATE_EXISTING)) {
                List<ByteBuffer> records = new ArrayList<>();
                seen.forEach((id, hop) -> records.add(encode(SEEN, id, hop, null)));
                for (StoredAgent a : live.values()) {
                    switch (a.phase()) {
                        case ACCEPTED -> records.add(encode(ACCEPTED, a.id(), a.hop(), a.image()));
                        case STARTED -> {
                            records.add(encode(ACCEPTED, a.id(), a.hop(), a.image()));
                            records.add(encode(STARTED, a.id(), a.hop(), null));
                        }
                        case DEPARTING -> records.add(encode(DEPARTING, a.id(), a.hop(), a.image()));
                    }
                }
                for (PendingEvent e : events.values()) {
                    records.add(encode(EVENT_PENDING, e.id(), e.seq(), e.event()));
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
            channel = FileChannel.open(journal, StandardOpenOption.WRITE);
            end = channel.size();
            allocated = end;
        }
    }
}
