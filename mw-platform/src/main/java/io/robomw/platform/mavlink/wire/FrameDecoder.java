package io.robomw.platform.mavlink.wire;

import java.util.Arrays;
import java.util.Objects;
import java.util.function.IntFunction;

/**
 * Cuts a byte stream (a serial link, or UDP datagrams one after the other) into MAVLink frames,
 * version 1 and 2. Bad bytes never stop it: it resynchronises on the next start byte.
 *
 * <h2>Rules, in the order they are applied</h2>
 * <ol>
 *   <li>Bytes before a start byte ({@code 0xFD}, {@code 0xFE}) are skipped (counted as dropped).</li>
 *   <li>A frame is complete when its header, its {@code len} payload bytes, its checksum and (when
 *   its signed flag is set) its 13 signature bytes have come; until then the decoder waits for
 *   more.</li>
 *   <li>A message id the dialect knows must have a good checksum (with its CRC_EXTRA): if not,
 *   only the start byte is skipped, and the search for a frame starts again at the next byte, so
 *   a real frame right behind a false start byte is still found.</li>
 *   <li>A frame with an incompatibility flag this codec does not know is dropped whole (counted),
 *   as the specification asks.</li>
 *   <li>A message id the dialect does not know cannot be checked, so its frame cannot be told from
 *   noise that happens to start with a start byte: it passes by unread. Only its start byte is
 *   skipped, and the search goes on inside it, as after a bad checksum (a real unknown frame hides
 *   no frame; noise that looks like one must not swallow the good frame behind it).</li>
 * </ol>
 * Over a serial link a false start byte holds the frames behind it until its claimed length has
 * come (at most {@value Framing#MAX_FRAME} bytes). A UDP datagram carries whole frames, so
 * {@link #feedDatagram} settles such a false start at the datagram's end instead of waiting for
 * the next datagrams.
 *
 * Signatures are not checked here: a {@link SignatureCheck} does it where the key is known.
 *
 * <p>Not thread-safe: one link's reader feeds it. Allocation: one byte array per frame handed on.
 */
public final class FrameDecoder {

    /** Receives every frame cut from the stream. */
    @FunctionalInterface
    public interface Sink {
        /**
         * @param frame a frame of a known message type with a good checksum
         */
        void frame(Frame frame);
    }

    /**
     * What a decoder has done so far.
     *
     * @param frames       frames handed on
     * @param unknown      start bytes skipped because the message id they announce is not in the dialect
     * @param badChecksums false starts and damaged frames (a known id with a wrong checksum)
     * @param incompatible frames dropped for an unknown incompatibility flag
     * @param droppedBytes bytes skipped while looking for a frame
     */
    public record Counts(long frames, long unknown, long badChecksums, long incompatible, long droppedBytes) {
    }

    private final IntFunction<MessageType> dialect;
    private final Sink sink;
    private final byte[] buffer = new byte[2 * Framing.MAX_FRAME];
    private int start;
    private int end;
    private long frames;
    private long unknown;
    private long badChecksums;
    private long incompatible;
    private long droppedBytes;

    /**
     * @param dialect the message types by id ({@link Messages#byId}); {@code null} for an unknown id
     * @param sink    receives the frames, on the feeding thread
     */
    public FrameDecoder(IntFunction<MessageType> dialect, Sink sink) {
        this.dialect = Objects.requireNonNull(dialect, "dialect");
        this.sink = Objects.requireNonNull(sink, "sink");
    }

    /**
     * Decodes the common dialect ({@link Messages}).
     *
     * @param sink receives the frames
     */
    public FrameDecoder(Sink sink) {
        this(Messages::byId, sink);
    }

    /**
     * Feeds bytes; every frame they complete goes to the sink before this returns.
     *
     * @param data   bytes
     * @param offset the first
     * @param length how many
     */
    public void feed(byte[] data, int offset, int length) {
        Objects.checkFromIndexSize(offset, length, data.length);
        int at = offset;
        int left = length;
        while (left > 0) {
            if (end == buffer.length) {
                compact();
            }
            int n = Math.min(left, buffer.length - end);
            System.arraycopy(data, at, buffer, end, n);
            end += n;
            at += n;
            left -= n;
            parse();
        }
    }

    /**
     * @param data bytes (a datagram)
     */
    public void feed(byte[] data) {
        feed(data, 0, data.length);
    }

    /**
     * Feeds one UDP datagram: its frames go to the sink, and bytes left at its end (a frame cut
     * short, or a false start byte) are dropped rather than kept for the next datagram.
     *
     * @param data   the datagram's buffer
     * @param offset its first byte
     * @param length its length
     */
    public void feedDatagram(byte[] data, int offset, int length) {
        feed(data, offset, length);
        while (end > start) {
            start++;
            droppedBytes++;
            parse();
        }
        start = 0;
        end = 0;
    }

    /** @return bytes held, waiting for the rest of a frame */
    public int pending() {
        return end - start;
    }

    /** @return what it has done so far */
    public Counts counts() {
        return new Counts(frames, unknown, badChecksums, incompatible, droppedBytes);
    }

    /** Forgets a partial frame (a link that was reopened). */
    public void reset() {
        start = 0;
        end = 0;
    }

    private void compact() {
        System.arraycopy(buffer, start, buffer, 0, end - start);
        end -= start;
        start = 0;
    }

    private void parse() {
        while (true) {
            int i = start;
            while (i < end && (buffer[i] & 0xFF) != Framing.STX_V2 && (buffer[i] & 0xFF) != Framing.STX_V1) {
                i++;
            }
            droppedBytes += i - start;
            start = i;
            if (end - start < 2) {
                if (start == end) {
                    start = 0;
                    end = 0;
                }
                return;
            }
            boolean v2 = (buffer[start] & 0xFF) == Framing.STX_V2;
            int header = v2 ? Framing.HEADER_V2 : Framing.HEADER_V1;
            if (end - start < header) {
                return;
            }
            int len = buffer[start + Framing.LEN] & 0xFF;
            int incompat = v2 ? buffer[start + Framing.INCOMPAT_FLAGS] & 0xFF : 0;
            int frameLength = header + len + Framing.CHECKSUM + ((incompat & Framing.INCOMPAT_SIGNED) != 0 ? Framing.SIGNATURE_BLOCK : 0);
            if (end - start < frameLength) {
                if (start > 0 && buffer.length - start < frameLength) {
                    compact();
                }
                return;
            }
            int id = v2 ? (buffer[start + Framing.MSGID] & 0xFF) | (buffer[start + Framing.MSGID + 1] & 0xFF) << 8
                    | (buffer[start + Framing.MSGID + 2] & 0xFF) << 16 : buffer[start + Framing.V1_MSGID] & 0xFF;
            MessageType type = dialect.apply(id);
            if (type != null) {
                int crc = Crc.accumulate(Crc.INITIAL, buffer, start + 1, header - 1 + len);
                crc = Crc.accumulate(crc, type.crcExtra());
                int sent = (buffer[start + header + len] & 0xFF) | (buffer[start + header + len + 1] & 0xFF) << 8;
                if (crc != sent) {
                    badChecksums++;
                    droppedBytes++;
                    start++;
                    continue;
                }
                if ((incompat & ~Framing.KNOWN_INCOMPAT_FLAGS) != 0) {
                    incompatible++;
                    start += frameLength;
                    continue;
                }
                frames++;
            } else {
                unknown++;
                droppedBytes++;
                start++;
                continue;
            }
            byte[] bytes = Arrays.copyOfRange(buffer, start, start + frameLength);
            start += frameLength;
            sink.frame(new Frame(bytes, v2 ? Frame.Version.V2 : Frame.Version.V1, type));
        }
    }
}
