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
     * @param atNanos when it was read ({@link System#nanoTime()})
     */
    public record Snapshot(int digital, int ex, int ey, long atNanos) {
    }

    private volatile Snapshot latest;
    private final java.util.concurrent.CompletableFuture<Void> firstPoll = new java.util.concurrent.CompletableFuture<>();

    /** @return completes when the first poll's inputs are published */
    public java.util.concurrent.CompletableFuture<Void> firstPoll() {
        return firstPoll;
    }

    void publish(int digital, int ex, int ey) {
        Snapshot previous = latest;
        latest = new Snapshot(digital, ex >= 0 ? ex : previous == null ? -1 : previous.ex(), ey >= 0 ? ey : previous == null ? -1 : previous.ey(),
                System.nanoTime());
        firstPoll.complete(null);
    }

    /** @return the latest inputs, or {@code null} before the first poll */
    public Snapshot latest() {
        return latest;
    }
}
