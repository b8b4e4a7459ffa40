package io.robomw.platform.motor;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;

/**
 * The hand-off of motor states from the action side to the link side, and of the stops waiting to
 * be on the wire: once per cycle the action side publishes the states it changed, as one batch
 * (under one lock, so motors started together are sent together); the link side takes everything
 * published whole, hands it to the driver, and puts it back if the link failed before it was
 * written (unless newer states were published meanwhile). A stop's future completes once the link
 * side has written every batch published up to the stop's cycle.
 *
 * <p>With the link side serviced inline (on the cycling thread, one thread at a time: a
 * simulation) the states move without the lock.
 */
final class MotorHandOff {

    private final MotorPort[] ports;
    /** Guards the ports' {@code published} states, the batch counts and the pending stops. */
    private final Object lock = new Object();
    private boolean inline;
    /** Whether any port has a published state not yet taken; written under the lock with a release store, read first without it. */
    private boolean anyPublished;
    /** The cycle whose states were published last; under the lock. */
    private long publishedCycle = Long.MAX_VALUE;
    /** The cycle whose published states the link side took last; link side. */
    private long servedCycle = 0; // none yet: a refusal in the first service concerns only the commands running when it began
    /** Batches published so far; under the lock. */
    private long publishedBatches;
    /** The count of published batches the link side took last; link side. */
    private long takenBatches;
    /** Batches written (all up to the count); written by the link side under the lock. */
    private long sentBatches;
    /** Stops waiting for the link side to write every batch up to theirs; under the lock. */
    private final List<PendingStop> pendingStops = new ArrayList<>(2);

    /** A stop waiting for the link side to write every batch up to {@code batch}. */
    private record PendingStop(long batch, CompletableFuture<Void> handed) {
    }

    MotorHandOff(MotorPort[] ports) {
        this.ports = ports;
    }

    /** The link side runs on the cycling thread, right after each publish: no lock is needed. Before the first cycle. */
    void inline() {
        inline = true;
    }

    // ---- action side ----

    /** Publishes the ports' changed states, as the batch of this cycle. */
    void publish(long cycle) {
        if (inline) {
            publishChanged(cycle);
        } else {
            synchronized (lock) {
                publishChanged(cycle);
            }
        }
    }

    private void publishChanged(long cycle) {
        publishedCycle = cycle;
        publishedBatches++;
        for (MotorPort p : ports) {
            if (p.changed != null) {
                p.published = p.changed;
                p.changed = null;
            }
        }
        ANY_PUBLISHED.setRelease(this, true);
    }

    /** Queues stops behind the batch published last (or completes them, when everything published is written). */
    void queueStops(List<CompletableFuture<Void>> stops) {
        List<CompletableFuture<Void>> done = null;
        synchronized (lock) {
            for (CompletableFuture<Void> handed : stops) {
                if (sentBatches >= publishedBatches) {
                    if (done == null) {
                        done = new ArrayList<>(stops.size());
                    }
                    done.add(handed);
                } else {
                    pendingStops.add(new PendingStop(publishedBatches, handed));
                }
            }
        }
        if (done != null) {
            done.forEach(f -> f.complete(null));
        }
    }

    /** Fails every stop still waiting to be written. */
    void failPendingStops(RuntimeException why) {
        List<PendingStop> failed;
        synchronized (lock) {
            if (pendingStops.isEmpty()) {
                return;
            }
            failed = List.copyOf(pendingStops);
            pendingStops.clear();
        }
        for (PendingStop s : failed) {
            s.handed().completeExceptionally(why);
        }
    }

    // ---- link side ----

    /**
     * Takes every published state into the ports' {@code draining}; with nothing published, clears
     * what a driver's exception left there.
     */
    void take() {
        if ((boolean) ANY_PUBLISHED.getAcquire(this)) {
            if (inline) {
                takePublished();
            } else {
                synchronized (lock) {
                    takePublished();
                }
            }
        } else {
            for (MotorPort p : ports) {
                p.draining = null;
            }
        }
    }

    private void takePublished() {
        servedCycle = publishedCycle;
        takenBatches = publishedBatches;
        for (MotorPort p : ports) {
            p.draining = p.published;
            p.published = null;
        }
        ANY_PUBLISHED.setRelease(this, false);
    }

    /** The link failed before the states taken were written: they go with the next service, unless newer ones were published. */
    void putBack() {
        synchronized (lock) {
            for (MotorPort p : ports) {
                if (p.draining != null && p.published == null) {
                    p.published = p.draining;
                    ANY_PUBLISHED.setRelease(this, true);
                }
            }
        }
    }

    /** The batch taken last is written: completes the stops that waited for it. */
    void written() {
        if (takenBatches <= sentBatches) {
            return;
        }
        List<CompletableFuture<Void>> done = null;
        synchronized (lock) {
            sentBatches = takenBatches;
            // no iterator: this runs after every batch a robot's link writes
            for (int i = 0; i < pendingStops.size(); ) {
                PendingStop s = pendingStops.get(i);
                if (s.batch() <= sentBatches) {
                    pendingStops.remove(i);
                    if (done == null) {
                        done = new ArrayList<>(2);
                    }
                    done.add(s.handed());
                } else {
                    i++;
                }
            }
        }
        if (done != null) {
            done.forEach(f -> f.complete(null));
        }
    }

    /**
     * @return the execution action thread's cycle whose states the link side took last: a refusal
     *         during a service concerns the commands admitted up to it, and those running when the
     *         service began; {@link Long#MAX_VALUE} when a publish did not say; 0 before the link side
     *         took any (not "every cycle": a driver that fails in its first service must not end the
     *         commands admitted after it began)
     */
    long servedCycle() {
        return servedCycle;
    }

    private static final VarHandle ANY_PUBLISHED;

    static {
        try {
            ANY_PUBLISHED = MethodHandles.lookup().findVarHandle(MotorHandOff.class, "anyPublished", boolean.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }
}
