package io.robomw.platform.motor;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;

/**
 * One motor port's state on both sides of the motor platform: what the action side wants, what it
 * published for the link side, and what the link side sent, read and predicted. One object per
 * port, fixed when the platform is built, instead of a map per kind keyed by port names: a cycle
 * touches each port's state in one place, and nothing is looked up by name.
 *
 * <p>Fields cross between the sides with release stores and acquire loads (plain moves on x86, no
 * fence per reading): one side writes each, the values are immutable records, and no decision
 * needs a store ordered before a later load of another field. A reading's two numbers are kept in
 * fields rather than an object per reading (two a cycle per robot: each a reference stored into
 * this long-lived object, a card for G1 to refine), behind a sequence lock: the link side writes
 * them (the version odd while it does, 0 before the first), any thread reads them whole.
 */
final class MotorPort {

    final String name;
    final int index;

    // ---- action side only ----
    /** The state the action side wants. */
    MotorState wanted;
    /** Set this cycle, published by the next flush, else {@code null}. */
    MotorState changed;

    // ---- guarded by the hand-off's lock ----
    /** Published for the link side, not yet taken. */
    MotorState published;

    // ---- link side only ----
    /** During a service: the state taken for this batch, and the one sent before it. */
    MotorState draining;
    MotorState sentBefore;
    /** The brick stopped a rotation meant to end braked at its limit: brake it with the next batch. */
    boolean brakeAtLimit;

    // ---- written by the link side, read by any thread ----
    private double readingDegrees;
    private long readingAtNanos;
    private int readingVersion;
    /** Where the motor was, by prediction, when the brick took the running state last sent for it. */
    private Start start;
    /** The last state handed to the driver. */
    private MotorState sent;
    /** A limited rotation the brick stopped by itself (or the link side stopped just in time). */
    private MotorState stoppedAtLimit;

    MotorPort(String name, int index) {
        this.name = name;
        this.index = index;
        this.wanted = MotorState.stopped(name, MotorState.StopMode.BRAKE);
    }

    /**
     * A rotation's state, where the motor was predicted to be when the brick took it, and when
     * that was ({@link Long#MAX_VALUE} while the driver is still sending it: a brick that takes
     * several packets to start a motor starts it only with the last).
     */
    static final class Start {
        private final MotorState state;
        private final double degrees;
        private volatile long sinceNanos;

        Start(MotorState state, double degrees, long sinceNanos) {
            this.state = state;
            this.degrees = degrees;
            this.sinceNanos = sinceNanos;
        }

        /** @return the running state sent */
        MotorState state() {
            return state;
        }

        /** @return where the motor was predicted to be when the brick took it */
        double degrees() {
            return degrees;
        }

        /** @return when the brick took it ({@link Long#MAX_VALUE} while it is being sent); read it once per use */
        long sinceNanos() {
            return sinceNanos;
        }

        /**
         * The driver has sent it: it counts from then (link side only). In place, not a new start
         * a batch: the link writes a batch at every change of every robot's drive.
         */
        void sent(long atNanos) {
            sinceNanos = atNanos;
        }
    }

    /** Records a reading; link side only (one writer at a time). */
    void reading(double degrees, long atNanos) {
        int version = readingVersion;
        READING_VERSION.setOpaque(this, version + 1);
        VarHandle.storeStoreFence();
        readingDegrees = degrees;
        readingAtNanos = atNanos;
        READING_VERSION.setRelease(this, version + 2);
    }

    /** @return the reading's version before reading its fields (then {@link #readingWhole}) */
    int readingBegin() {
        return (int) READING_VERSION.getAcquire(this);
    }

    /**
     * @param version what {@link #readingBegin} returned before the fields were read
     * @return whether the fields read since were one whole reading (else read again: the link side
     *         was writing them, two stores)
     */
    boolean readingWhole(int version) {
        VarHandle.loadLoadFence();
        return (version & 1) == 0 && (int) READING_VERSION.getOpaque(this) == version;
    }

    /** @return the last reading's degrees (read between {@link #readingBegin} and {@link #readingWhole}) */
    double readingDegreesRaw() {
        return readingDegrees;
    }

    /** @return when the last reading was taken (read between {@link #readingBegin} and {@link #readingWhole}) */
    long readingAtNanosRaw() {
        return readingAtNanos;
    }

    /** @return the last reading's degrees, 0 before the first */
    double readingDegrees() {
        while (true) {
            int version = readingBegin();
            double degrees = readingDegrees;
            if (readingWhole(version)) {
                return degrees;
            }
            Thread.onSpinWait();
        }
    }

    Start start() {
        return (Start) START.getAcquire(this);
    }

    void start(Start st) {
        START.setRelease(this, st);
    }

    MotorState sent() {
        return (MotorState) SENT.getAcquire(this);
    }

    void sent(MotorState st) {
        SENT.setRelease(this, st);
    }

    MotorState stoppedAtLimit() {
        return (MotorState) STOPPED_AT_LIMIT.getAcquire(this);
    }

    void stoppedAtLimit(MotorState st) {
        STOPPED_AT_LIMIT.setRelease(this, st);
    }

    private static final VarHandle READING_VERSION;
    private static final VarHandle START;
    private static final VarHandle SENT;
    private static final VarHandle STOPPED_AT_LIMIT;

    static {
        try {
            MethodHandles.Lookup l = MethodHandles.lookup();
            READING_VERSION = l.findVarHandle(MotorPort.class, "readingVersion", int.class);
            START = l.findVarHandle(MotorPort.class, "start", Start.class);
            SENT = l.findVarHandle(MotorPort.class, "sent", MotorState.class);
            STOPPED_AT_LIMIT = l.findVarHandle(MotorPort.class, "stoppedAtLimit", MotorState.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }
}
