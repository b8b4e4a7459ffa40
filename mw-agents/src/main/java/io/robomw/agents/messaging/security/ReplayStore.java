package io.robomw.agents.messaging.security;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.nio.MappedByteBuffer;
import java.nio.channels.FileChannel;
import java.nio.channels.FileLock;
import java.nio.channels.OverlappingFileLockException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.nio.file.attribute.PosixFilePermissions;
import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.time.Duration;
import java.util.HashMap;
import java.util.HexFormat;
import java.util.Map;

/**
 * A receiving node's replay window, kept on disk so that it survives a restart (as Kerberos keeps
 * its replay cache): for each source whose authenticated frames the node took within the allowed
 * clock skew, the highest message number taken. After a restart, a frame of such a source
 * numbered at or below it is a replay ({@link io.robomw.agents.messaging.DropReason#REPLAYED});
 * sources last seen longer ago than twice the skew need no entry, since their frames are refused
 * as stale anyway. So a captured signed message, robot command or agent event replayed to a
 * restarted receiver is refused.
 *
 * <p>The file is memory-mapped: every entry is written as the frame is taken, into the page cache,
 * so a node killed with {@code kill -9} loses nothing of it (a power cut may lose the last
 * seconds). One process at a time holds a node's file (a file lock); another process running a
 * node of the same name keeps its window in memory only, and says so.
 *
 * <pre>
 * header  [magic "RMRW" 4][version u16: 1][reserved u16: 0][slots u32][reserved u32: 0]
 * slot    [source 8][highest message number 8][last taken, ms since the epoch 8]   (last taken 0: free)
 * </pre>
 * All integers big-endian. A file of another version or size is refused with an error naming it
 * (logged; the node then keeps its window in memory only, as before this store existed).
 * Thread-safe.
 */
public final class ReplayStore implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(ReplayStore.class);

    /** The first bytes of the file. */
    public static final byte[] MAGIC = "RMRW".getBytes(StandardCharsets.US_ASCII);
    /** The version this class reads and writes. */
    public static final int VERSION = 1;
    /** Sources it remembers at once; beyond them the one taken longest ago is forgotten. */
    public static final int SLOTS = 4096;
    static final int HEADER = 16;
    static final int SLOT = 24;

    private final Path file;
    private final long keepMillis;
    private final Map<Long, Integer> slots = new HashMap<>();
    private final Map<Long, Long> floors = new HashMap<>();
    private boolean opened;
    private FileChannel channel;
    private FileLock lock;
    private MappedByteBuffer map;

    private ReplayStore(Path file, Duration keep) {
        this.file = file;
        this.keepMillis = keep.toMillis();
    }

    /** @return a store that keeps nothing across restarts */
    public static ReplayStore memoryOnly() {
        return new ReplayStore(null, Duration.ZERO);
    }

    /**
     * A store in a file, opened when first needed (a node that never takes an authenticated frame makes no file).
     *
     * @param file the file
     * @param keep how long an entry matters: twice the allowed clock skew (a frame taken now may be timestamped up to the skew ahead)
     * @return the store
     */
    public static ReplayStore in(Path file, Duration keep) {
        return new ReplayStore(file, keep);
    }

    /**
     * @param dir  the folder of the user's replay stores
     * @param node a node's name
     * @return the file of that node's store: its name where it is a plain file name, with a hash of it otherwise
     */
    public static Path fileFor(Path dir, String node) {
        String plain = node.replaceAll("[^A-Za-z0-9._-]", "_");
        if (plain.length() > 80) {
            plain = plain.substring(0, 80);
        }
        if (!plain.equals(node) || plain.startsWith(".")) {
            try {
                byte[] h = MessageDigest.getInstance("SHA-256").digest(node.getBytes(StandardCharsets.UTF_8));
                plain = plain + "-" + HexFormat.of().formatHex(h, 0, 4);
            } catch (NoSuchAlgorithmException e) {
                throw new IllegalStateException(e);
            }
        }
        return dir.resolve(plain + ".replay");
    }

    /**
     * @param source a frame's source
     * @return the highest number taken from it before this node started (within the skew), or {@link Long#MIN_VALUE}
     */
    public synchronized long floor(long source) {
        open();
        Long f = floors.get(source);
        return f == null ? Long.MIN_VALUE : f;
    }

    /**
     * Records an authenticated frame the node took.
     *
     * @param source     its source
     * @param number     its message number
     * @param nowMillis  this host's clock
     */
    public synchronized void record(long source, long number, long nowMillis) {
        open();
        if (map == null) {
            return;
        }
        Integer slot = slots.get(source);
        if (slot == null) {
            slot = freeSlot(source, nowMillis);
            slots.put(source, slot);
            map.putLong(at(slot), source);
            map.putLong(at(slot) + 8, number);
        } else if (number > map.getLong(at(slot) + 8)) {
            map.putLong(at(slot) + 8, number);
        }
        map.putLong(at(slot) + 16, nowMillis);
    }

    private int freeSlot(long source, long nowMillis) {
        int start = Math.floorMod(Long.hashCode(source * 0x9E3779B97F4A7C15L), SLOTS);
        int oldest = start;
        long oldestSeen = Long.MAX_VALUE;
        for (int i = 0; i < SLOTS; i++) {
            int s = (start + i) % SLOTS;
            long seen = map.getLong(at(s) + 16);
            if (seen == 0 || nowMillis - seen > keepMillis) {
                forget(s);
                return s;
            }
            if (seen < oldestSeen) {
                oldestSeen = seen;
                oldest = s;
            }
        }
        forget(oldest);
        return oldest;
    }

    private void forget(int slot) {
        long was = map.getLong(at(slot));
        if (map.getLong(at(slot) + 16) != 0) {
            slots.remove(was, slot);
        }
        map.putLong(at(slot) + 16, 0);
    }

    private static int at(int slot) {
        return HEADER + slot * SLOT;
    }

    private void open() {
        if (opened) {
            return;
        }
        opened = true;
        if (file == null) {
            return;
        }
        try {
            Path dir = file.toAbsolutePath().getParent();
            if (!Files.isDirectory(dir)) {
                Files.createDirectories(dir, PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString("rwx------")));
            }
            channel = FileChannel.open(file, StandardOpenOption.CREATE, StandardOpenOption.READ, StandardOpenOption.WRITE);
            try {
                lock = channel.tryLock();
            } catch (OverlappingFileLockException e) {
                lock = null;
            }
            if (lock == null) {
                LOG.info("replay store {} is in use by another node of that name; this one keeps its replay window in memory only", file);
                channel.close();
                channel = null;
                return;
            }
            long size = HEADER + (long) SLOTS * SLOT;
            long existing = channel.size();
            if (existing != 0 && existing != size) {
                closeQuietly();
                throw new IllegalStateException("the replay store " + file + " is " + existing + " bytes, not the " + size
                        + " this RoboMW reads: move it away, and the node starts with an empty one");
            }
            map = channel.map(FileChannel.MapMode.READ_WRITE, 0, size);
            if (existing == 0) {
                map.put(0, MAGIC).putShort(4, (short) VERSION).putShort(6, (short) 0).putInt(8, SLOTS).putInt(12, 0);
            } else {
                check(existing, size);
                load(System.currentTimeMillis());
            }
        } catch (IllegalStateException e) {
            LOG.error("{}; until then this node's replay window lasts only while it runs", e.getMessage());
        } catch (IOException e) {
            LOG.warn("cannot use the replay store {} ({}): this node's replay window lasts only while it runs", file, e.toString());
            closeQuietly();
        }
    }

    private void check(long existing, long size) throws IOException {
        byte[] magic = new byte[MAGIC.length];
        map.get(0, magic);
        int version = map.getShort(4) & 0xFFFF;
        if (!java.util.Arrays.equals(magic, MAGIC) || existing != size || version != VERSION || map.getInt(8) != SLOTS) {
            closeQuietly();
            throw new IllegalStateException("the replay store " + file + " is not one this RoboMW reads (magic " + HexFormat.of().formatHex(magic)
                    + ", version " + version + ", " + existing + " bytes; this build reads version " + VERSION + " of " + size
                    + " bytes): move it away, and the node starts with an empty one");
        }
    }

    private void load(long nowMillis) {
        for (int s = 0; s < SLOTS; s++) {
            long seen = map.getLong(at(s) + 16);
            if (seen == 0) {
                continue;
            }
            if (nowMillis - seen > keepMillis) {
                map.putLong(at(s) + 16, 0);
                continue;
            }
            long source = map.getLong(at(s));
            slots.put(source, s);
            floors.put(source, map.getLong(at(s) + 8));
        }
        LOG.debug("replay store {}: {} sources from before this start", file, floors.size());
    }

    @Override
    public synchronized void close() {
        if (map != null) {
            map.force();
        }
        closeQuietly();
    }

    private void closeQuietly() {
        map = null;
        try {
            if (lock != null) {
                lock.release();
            }
            if (channel != null) {
                channel.close();
            }
        } catch (IOException e) {
            LOG.debug("closing the replay store {}: {}", file, e.toString());
        }
        lock = null;
        channel = null;
    }

    /** @return the file, or {@code null} for a store in memory only */
    public Path file() {
        return file;
    }
}
