package io.robomw.platform.testkit;

import java.time.Duration;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CountDownLatch;

/**
 * What the far end of a {@link ScriptedLink} sends back for one write (or one frame of it): pieces
 * of bytes, each a read's worth at most, arriving at once, after a delay on the link's clock, at a
 * given time on it, or once a latch is released. Immutable; each method returns a new answer.
 *
 * <pre>{@code
 * Answer.of(reply)                                   // one piece, at once
 * Answer.inPieces(List.of(head, tail)).after(ms(5))  // two pieces, 5 ms after the write
 * Answer.of(echo).and(Answer.of(reply).after(ms(3))) // the echo at once, the reply later
 * Answer.of(reply).heldUntil(release)                // once the test counts the latch down
 * }</pre>
 */
public final class Answer {

    /** One piece: its bytes and when it arrives. */
    record Piece(byte[] bytes, Timing timing, long nanos, CountDownLatch hold) {
    }

    /** How a piece's {@code nanos} reads. */
    enum Timing {
        /** {@code nanos} after the write, on the link's clock. */
        AFTER_THE_WRITE,
        /** At {@code nanos} on the link's clock. */
        AT
    }

    private static final Answer NONE = new Answer(List.of());

    private final List<Piece> pieces;

    private Answer(List<Piece> pieces) {
        this.pieces = List.copyOf(pieces);
    }

    /** @return no answer: the far end stays silent */
    public static Answer none() {
        return NONE;
    }

    /**
     * @param bytes what arrives, as one piece (a read returns it, or part of it); empty is {@link #none()}
     * @return the bytes, arriving at once
     */
    public static Answer of(byte[] bytes) {
        return inPieces(List.of(bytes));
    }

    /**
     * @param pieces what arrives, piece by piece (each read returns at most one); empty pieces are left out
     * @return the pieces, arriving at once, in order
     */
    public static Answer inPieces(List<byte[]> pieces) {
        List<Piece> out = new ArrayList<>();
        for (byte[] p : pieces) {
            Objects.requireNonNull(p, "an answer's piece is null: answer Answer.none() for silence");
            if (p.length > 0) {
                out.add(new Piece(p.clone(), Timing.AFTER_THE_WRITE, 0, null));
            }
        }
        return out.isEmpty() ? NONE : new Answer(out);
    }

    /**
     * @param bytes what arrives
     * @return the bytes one byte a piece, so that each read returns one byte
     */
    public static Answer oneByteAtATime(byte[] bytes) {
        List<byte[]> out = new ArrayList<>();
        for (byte b : bytes) {
            out.add(new byte[] {b});
        }
        return inPieces(out);
    }

    /**
     * @param delay how long after the write every piece of this answer arrives, measured on the
     *              link's clock; replaces any earlier timing
     * @return the answer, delayed
     */
    public Answer after(Duration delay) {
        if (delay.isNegative()) {
            throw new IllegalArgumentException("an answer cannot arrive before its question, delay=" + delay);
        }
        return retimed(Timing.AFTER_THE_WRITE, delay.toNanos());
    }

    /**
     * @param clockNanos when every piece of this answer arrives, on the link's clock (its
     *                   {@code nanoTime()}); a time already past arrives at once
     * @return the answer, due then
     */
    public Answer dueAt(long clockNanos) {
        return retimed(Timing.AT, clockNanos);
    }

    /**
     * @param release the latch that holds every piece of this answer back until it reaches zero
     *                (and its time, if any, has come)
     * @return the answer, held
     */
    public Answer heldUntil(CountDownLatch release) {
        Objects.requireNonNull(release, "release");
        return new Answer(pieces.stream().map(p -> new Piece(p.bytes(), p.timing(), p.nanos(), release)).toList());
    }

    /**
     * @param next what the far end sends after this, with its own timing
     * @return this answer's pieces, then {@code next}'s (pieces due at the same time arrive in this order)
     */
    public Answer and(Answer next) {
        List<Piece> both = new ArrayList<>(pieces);
        both.addAll(next.pieces);
        return new Answer(both);
    }

    /** @return whether the far end sends nothing */
    public boolean isEmpty() {
        return pieces.isEmpty();
    }

    List<Piece> pieces() {
        return pieces;
    }

    private Answer retimed(Timing timing, long nanos) {
        return new Answer(pieces.stream().map(p -> new Piece(p.bytes(), timing, nanos, p.hold())).toList());
    }

    @Override
    public String toString() {
        return pieces.stream().map(p -> Arrays.toString(p.bytes())).toList().toString();
    }
}
