package io.robomw.agents.messaging.shm;

import io.robomw.agents.messaging.DropReason;
import io.robomw.agents.messaging.frame.FrameException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.lang.invoke.VarHandle;
import java.lang.reflect.Field;
import java.lang.reflect.Method;
import java.nio.ByteBuffer;
import java.nio.ByteOrder;
import java.nio.MappedByteBuffer;
import java.nio.channels.FileChannel;
import java.nio.file.Files;
import java.nio.file.LinkOption;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.nio.file.attribute.PosixFileAttributes;

/**
 * A subscriber's mapping of a publisher's segment: the control area read-write (only its own cell
 * is written), the ring read-only (a subscriber cannot spoil what others read). Takes payloads out
 * by {@link SharedReference}, checking each against the segment, and releases their records.
 *
 * <p>Not thread-safe: one reading thread per connection, which also {@link #close}s it.
 */
public final class SegmentView implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(SegmentView.class);

    private final Path file;
    private final String peer;
    private final int cell;
    private final int dataBytes;
    private final int maxPayload;
    private MappedByteBuffer control;
    private MappedByteBuffer data;
    private long lastSequence;

    private SegmentView(Path file, String peer, int cell, int dataBytes, int maxPayload, MappedByteBuffer control, MappedByteBuffer data) {
        this.maxPayload = maxPayload;
        this.file = file;
        this.peer = peer;
        this.cell = cell;
        this.dataBytes = dataBytes;
        this.control = control;
        this.data = data;
    }

    /**
     * Maps an offered segment, after checking that it is one: a regular file (not a link) directly
     * in {@code directory}, named as segments are, owned by this process's user and not readable
     * by others; its header has the magic, version and nonce of the offer and a cell for this one.
     *
     * @param directory where segments are ({@link SharedSegment#DIRECTORY})
     * @param offer     the offer
     * @param peer      the publisher, for messages
     * @param maxPayload the largest payload taken out (the node's maximum frame size: what it would take over TCP)
     * @return the view
     * @throws IOException naming the file and what is wrong, if it is not such a segment or cannot be mapped
     */
    public static SegmentView open(Path directory, Handshake.Offer offer, String peer, int maxPayload) throws IOException {
        Path file = offer.file();
        if (!directory.equals(file.getParent()) || !file.getFileName().toString().startsWith(SegmentLayout.FILE_PREFIX)) {
            throw new IOException(peer + " offered " + file + ", which is not a segment file in " + directory);
        }
        PosixFileAttributes attributes = Files.readAttributes(file, PosixFileAttributes.class, LinkOption.NOFOLLOW_LINKS);
        if (!attributes.isRegularFile()) {
            throw new IOException(peer + " offered " + file + ", which is not a regular file");
        }
        if (!attributes.owner().getName().equals(System.getProperty("user.name"))) {
            throw new IOException(peer + " offered " + file + ", owned by " + attributes.owner().getName() + ", not by this process's user");
        }
        try (FileChannel ch = FileChannel.open(file, StandardOpenOption.READ, StandardOpenOption.WRITE, LinkOption.NOFOLLOW_LINKS)) {
            long size = ch.size();
            if (size < SegmentLayout.CELLS_OFFSET) {
                throw new IOException(peer + " offered " + file + " of " + size + " bytes, too small for a segment");
            }
            ByteBuffer head = ByteBuffer.allocate(SegmentLayout.CELLS_OFFSET).order(ByteOrder.nativeOrder());
            while (head.hasRemaining() && ch.read(head, head.position()) > 0) {
                // reads the header
            }
            long magic = head.getLong(SegmentLayout.MAGIC_OFFSET);
            int version = head.getInt(SegmentLayout.VERSION_OFFSET);
            int cells = head.getInt(SegmentLayout.CELL_COUNT_OFFSET);
            long nonce = head.getLong(SegmentLayout.NONCE_OFFSET);
            int dataOffset = head.getInt(SegmentLayout.DATA_OFFSET_OFFSET);
            int dataBytes = head.getInt(SegmentLayout.DATA_BYTES_OFFSET);
            if (magic != SegmentLayout.MAGIC || version != SegmentLayout.VERSION) {
                throw new IOException(peer + " offered " + file + ": magic 0x" + Long.toHexString(magic) + " version " + version
                        + ", expected 0x" + Long.toHexString(SegmentLayout.MAGIC) + " version " + SegmentLayout.VERSION);
            }
            if (nonce != offer.nonce()) {
                throw new IOException(peer + " offered " + file + ", whose nonce is not the offer's: another file of that name (another host or container?)");
            }
            if (cells <= 0 || offer.cell() < 0 || offer.cell() >= cells || dataOffset != SegmentLayout.controlBytes(cells)
                    || dataBytes <= 0 || dataBytes % SegmentLayout.ALIGNMENT != 0 || (long) dataOffset + dataBytes != size) {
                throw new IOException(peer + " offered cell " + offer.cell() + " of " + file + " with " + cells + " cells, ring at " + dataOffset
                        + " of " + dataBytes + " bytes, file of " + size + " bytes: not a consistent segment");
            }
            MappedByteBuffer control = ch.map(FileChannel.MapMode.READ_WRITE, 0, dataOffset);
            MappedByteBuffer data = ch.map(FileChannel.MapMode.READ_ONLY, dataOffset, dataBytes);
            control.order(ByteOrder.nativeOrder());
            data.order(ByteOrder.nativeOrder());
            return new SegmentView(file, peer, offer.cell(), dataBytes, maxPayload, control, data);
        }
    }

    /** @return the mapped file */
    public Path file() {
        return file;
    }

    /**
     * Copies a payload out and releases its record.
     *
     * @param ref the reference, as received
     * @return the payload
     * @throws FrameException ({@link DropReason#MALFORMED}) naming the reference and the rule if it lies outside the
     *                        ring, does not follow the last one, or does not match the record it names
     *                        ({@link DropReason#OVERSIZED} if its payload is above the maximum); the caller ends the connection
     */
    public byte[] take(SharedReference ref) throws FrameException {
        if (data == null) {
            throw new FrameException(DropReason.MALFORMED, "shared-memory reference " + ref + " from " + peer + " after its segment was closed");
        }
        long offset = ref.offset() & 0xFFFFFFFFL;
        long length = ref.length() & 0xFFFFFFFFL;
        if (offset % SegmentLayout.ALIGNMENT != 0 || offset + SegmentLayout.RECORD_HEADER + length > dataBytes) {
            throw new FrameException(DropReason.MALFORMED, "shared-memory reference " + ref + " from " + peer + " lies outside the "
                    + dataBytes + "-byte ring of " + file + " (or is not " + SegmentLayout.ALIGNMENT + "-aligned)");
        }
        if (length > maxPayload) {
            throw new FrameException(DropReason.OVERSIZED, "shared-memory reference " + ref + " from " + peer + " names a payload of " + length
                    + " bytes, above the maximum frame size of " + maxPayload);
        }
        if (ref.sequence() <= lastSequence) {
            throw new FrameException(DropReason.MALFORMED, "shared-memory reference " + ref + " from " + peer + " does not follow the last one, "
                    + lastSequence + ": references come in increasing sequence");
        }
        int at = (int) offset;
        long seq = (long) SegmentLayout.LONG.getAcquire((ByteBuffer) data, at);
        int recorded = data.getInt(at + SegmentLayout.RECORD_LENGTH_OFFSET);
        if (seq != ref.sequence() || recorded != ref.length()) {
            throw new FrameException(DropReason.MALFORMED, "shared-memory reference " + ref + " from " + peer + " names a record that holds sequence "
                    + seq + " of " + recorded + " bytes in " + file);
        }
        byte[] payload = new byte[(int) length];
        data.get(at + SegmentLayout.RECORD_HEADER, payload, 0, payload.length);
        VarHandle.acquireFence();
        if ((long) SegmentLayout.LONG.getVolatile((ByteBuffer) data, at) != seq) {
            throw new FrameException(DropReason.MALFORMED, "shared-memory record " + ref.sequence() + " from " + peer + " was overwritten while it was"
                    + " copied out of " + file + ": the publisher reused it too early");
        }
        lastSequence = seq;
        SegmentLayout.LONG.setRelease((ByteBuffer) control, SegmentLayout.cellOffset(cell), seq);
        return payload;
    }

    /** Drops the mapping (unmapped at once where the JDK allows it). Call on the reading thread. Idempotent. */
    @Override
    public void close() {
        MappedByteBuffer c = control;
        MappedByteBuffer d = data;
        control = null;
        data = null;
        if (d != null) {
            Unmapper.unmap(c);
            Unmapper.unmap(d);
        }
    }

    @Override
    public String toString() {
        return "SegmentView[" + file + ", cell " + cell + "]";
    }

    /**
     * Unmaps a buffer at once through {@code sun.misc.Unsafe.invokeCleaner} (module jdk.unsupported,
     * as Agrona and Netty do), else leaves it to the garbage collector. Only for a buffer nothing reads any more.
     */
    private static final class Unmapper {
        private static final Object UNSAFE;
        private static final Method CLEANER;

        static {
            Object unsafe = null;
            Method cleaner = null;
            try {
                Class<?> type = Class.forName("sun.misc.Unsafe");
                Field f = type.getDeclaredField("theUnsafe");
                f.setAccessible(true);
                unsafe = f.get(null);
                cleaner = type.getMethod("invokeCleaner", ByteBuffer.class);
            } catch (ReflectiveOperationException | RuntimeException e) {
                LOG.debug("mappings are dropped by the garbage collector: {}", e.toString());
            }
            UNSAFE = unsafe;
            CLEANER = cleaner;
        }

        static void unmap(ByteBuffer b) {
            if (CLEANER == null || b == null) {
                return;
            }
            try {
                CLEANER.invoke(UNSAFE, b);
            } catch (ReflectiveOperationException | RuntimeException e) {
                LOG.debug("cannot unmap: {}", e.toString());
            }
        }
    }
}
