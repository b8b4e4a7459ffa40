package io.robomw.platform.ft.intelligent;

/**
 * The interface's inputs as last polled, published by the link thread for sensor reads on any
 * thread: the digital byte and the two analog values, with when they were read. Immutable
 * snapshots behind one volatile reference.
 */
public final class IntelligentInterfaceInputs {

    /**
     * One poll's inputs.
     *
     * @param digital bit i = E(i+1)
     * @param ex      EX, 0..1023, or −1 before it was first read
     * @param ey      EY, 0..1023, or −1 before it was first read
     * @param atNanos when it was read (the platform's clock)
     */
    public record Snapshot(int digital, int ex, int ey, long atNanos) {
    }

    private final io.robomw.api.Clock clock;
    private volatile Snapshot latest;

    /** @param clock the platform's clock, which dates the polls */
    public IntelligentInterfaceInputs(io.robomw.api.Clock clock) {
        this.clock = java.util.Objects.requireNonNull(clock, "clock");
    }

    /** @return how long ago, on the platform's clock, a snapshot was read */
    public long ageNanos(Snapshot s) {
        return clock.nanoTime() - s.atNanos();
    }
    private final java.util.concurrent.CompletableFuture<Void> firstPoll = new java.util.concurrent.CompletableFuture<>();

    /** @return completes when the first poll's inputs are published */
    public java.util.concurrent.CompletableFuture<Void> firstPoll() {
        return firstPoll;
    }

    void publish(int digital, int ex, int ey) {
        Snapshot previous = latest;
        latest = new Snapshot(digital, ex >= 0 ? ex : previous == null ? -1 : previous.ex(), ey >= 0 ? ey : previous == null ? -1 : previous.ey(),
                clock.nanoTime());
        firstPoll.complete(null);
    }

    /** @return the latest inputs, or {@code null} before the first poll */
    public Snapshot latest() {
        return latest;
    }
}
