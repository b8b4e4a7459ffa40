package io.robomw.agents.messaging.shm;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.nio.ByteOrder;

/**
 * The layout of a shared-memory segment file ({@code /dev/shm/robomw-shm-<pid>-<random>}): a control
 * area, then the ring of records. Both sides run on one host, so every integer is in the host's
 * native byte order; the cells and each record's sequence are read and written with
 * acquire/release {@link VarHandle}s over the mapped buffers.
 *
 * <pre>
 * control area (CONTROL_BYTES, a multiple of 4096)
 *   0  MAGIC          u64  0x524D53484D534547 ("RMSHMSEG")
 *   8  VERSION        u32  1
 *  12  CELL COUNT     u32  consumed-sequence cells, one per subscriber connection
 *  16  NONCE          u64  random, also sent in the offer: the subscriber proves it mapped this very file
 *  24  DATA OFFSET    u32  where the ring starts (= CONTROL_BYTES)
 *  28  DATA BYTES     u32  the ring's size
 *  32  reserved to 64
 *  64 + 64 i          u64  cell i: the sequence of the last record subscriber i copied out (0: none);
 *                          written by that subscriber only, each in a cache line of its own
 * ring (DATA BYTES), records back to back, each 8-aligned, none split by the ring's end:
 *   0  SEQUENCE       u64  written last (release): the record is whole once it reads as the reference's
 *   8  LENGTH         u32  the payload's length
 *  12  reserved       u32
 *  16  PAYLOAD
 * </pre>
 *
 * <p>Stateless.
 */
public final class SegmentLayout {

    /** "RMSHMSEG". */
    public static final long MAGIC = 0x524D53484D534547L;
    /** The layout's version. */
    public static final int VERSION = 1;
    public static final int MAGIC_OFFSET = 0;
    public static final int VERSION_OFFSET = 8;
    public static final int CELL_COUNT_OFFSET = 12;
    public static final int NONCE_OFFSET = 16;
    public static final int DATA_OFFSET_OFFSET = 24;
    public static final int DATA_BYTES_OFFSET = 28;
    /** Where cell 0 is. */
    public static final int CELLS_OFFSET = 64;
    /** Bytes per cell: one cache line, so subscribers do not write each other's lines. */
    public static final int CELL_BYTES = 64;
    /** A record's head before its payload. */
    public static final int RECORD_HEADER = 16;
    public static final int RECORD_LENGTH_OFFSET = 8;
    /** Records start at multiples of this. */
    public static final int ALIGNMENT = 8;
    /** The prefix of every segment file's name; the publisher's process id follows. */
    public static final String FILE_PREFIX = "robomw-shm-";

    /** Reads and writes a long of a mapped buffer with the memory order asked for. */
    static final VarHandle LONG = MethodHandles.byteBufferViewVarHandle(long[].class, ByteOrder.nativeOrder());

    private SegmentLayout() {
    }

    /**
     * @param cells how many cells
     * @return the control area's size: the header and the cells, rounded up to a page
     */
    public static int controlBytes(int cells) {
        int raw = CELLS_OFFSET + cells * CELL_BYTES;
        return (raw + 4095) & ~4095;
    }

    /** @param cell a cell @return where it is in the control area */
    public static int cellOffset(int cell) {
        return CELLS_OFFSET + cell * CELL_BYTES;
    }

    /** @param payloadLength a payload's length @return the bytes its record takes in the ring, aligned */
    public static int recordBytes(int payloadLength) {
        return (RECORD_HEADER + payloadLength + ALIGNMENT - 1) & ~(ALIGNMENT - 1);
    }
}
