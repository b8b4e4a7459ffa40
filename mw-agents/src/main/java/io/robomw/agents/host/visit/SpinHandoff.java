package io.robomw.agents.host.visit;

import java.time.Duration;
import java.util.AbstractQueue;
import java.util.Collection;
import java.util.Iterator;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.SynchronousQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.LongSupplier;

/**
 * The hand-off queue of a host's runner pool: like the {@link SynchronousQueue} of a cached
 * thread pool (a task is taken only by an idle thread, else the pool starts one), but an idle
 * thread first spins for a bounded time ({@code spin}), yielding the processor to any thread
 * that has work, before it parks. A task handed over while
 * a thread spins starts at once; waking a parked thread costs tens of microseconds on the
 * project's virtual machines, about a fifth of a warm agent round trip. A spin of zero (the
 * default on a machine with one processor, where a spinning thread only delays the one that
 * would hand it work) never spins, and this is then a {@link SynchronousQueue}.
 *
 * <p>An idle thread spins only while {@code worthSpinning} says so: a host's runners, while the
 * host has had few agents at once lately (no more runner threads than eight times the processors).
 * With many at work, a task rarely finds a processor idle to spin on, and every thread that spun
 * took one from the threads with work: a thousand agents hopping among four hosts that share two
 * processors hopped with about twice the p99 with spinning runners as without (docs/benchmarks.md,
 * "Many agents at once").
 *
 * <p>How a task never strands: {@code unclaimed} counts the spinning threads no task has claimed.
 * An offer claims one (decrements it; none left: the task goes to a parked thread, or to none and
 * the pool starts a thread for it) and then puts its task in the slot; a spinning thread takes a
 * task from the slot, or leaves by giving back an unclaimed place. With none unclaimed, every
 * spinning thread has a task on its way, so it stays until it takes one: the spinning threads are
 * always the unclaimed ones plus the tasks claimed and not yet taken.
 *
 * <p>Only what {@link java.util.concurrent.ThreadPoolExecutor} uses is supported: offer, poll
 * with a timeout, take, drain, remove, size.
 *
 * @param <E> the tasks
 */
public final class SpinHandoff<E> extends AbstractQueue<E> implements BlockingQueue<E> {

    private final SynchronousQueue<E> parked = new SynchronousQueue<>();
    private final ConcurrentLinkedQueue<E> slot = new ConcurrentLinkedQueue<>();
    private final AtomicInteger unclaimed = new AtomicInteger();
    private final AtomicInteger spinning = new AtomicInteger();
    private final long spinNanos;
    private final java.util.function.BooleanSupplier worthSpinning;
    private final LongSupplier nanoTime;
    /** Set by a task on its own thread: that thread's next wait for a task parks without spinning ({@link #parkNext}). */
    private final ThreadLocal<boolean[]> parkNext = ThreadLocal.withInitial(() -> new boolean[1]);

    /**
     * @param spin     how long an idle thread spins before it parks; zero never spins
     * @param nanoTime the clock the spin is measured on
     */
    public SpinHandoff(Duration spin, LongSupplier nanoTime) {
        this(spin, () -> true, nanoTime);
    }

    /**
     * @param spin          how long an idle thread spins before it parks; zero never spins
     * @param worthSpinning asked as a thread becomes idle: whether it spins (else it parks at once)
     * @param nanoTime      the clock the spin is measured on
     */
    public SpinHandoff(Duration spin, java.util.function.BooleanSupplier worthSpinning, LongSupplier nanoTime) {
        if (spin.isNegative()) {
            throw new IllegalArgumentException("a runner spin must be >= 0, got " + spin);
        }
        this.spinNanos = spin.toNanos();
        this.worthSpinning = worthSpinning;
        this.nanoTime = nanoTime;
    }

    /**
     * @return the spin a host's runners use unless told: 150 µs, none on a machine with one processor.
     *         Long enough to outlast a warm A→B→A round trip on the agent wire (about 45-110 µs on the
     *         project's machine), so the runner that sent an agent on is still spinning when it comes
     *         back (docs/benchmarks.md, "Agent hops on the agent wire")
     */
    public static Duration defaultSpin() {
        return Runtime.getRuntime().availableProcessors() > 1 ? Duration.ofNanos(150_000) : Duration.ZERO;
    }

    /**
     * @return how long a transfer on the agent wire spins for its acknowledgement unless told: 50 µs,
     *         none on a machine with one processor. The acknowledgement comes within tens of
     *         microseconds (the receiver stores the agent and answers), and a sender that spun for it
     *         goes back to the runner pool at once rather than after a wake-up
     */
    public static Duration defaultWireSpin() {
        return Runtime.getRuntime().availableProcessors() > 1 ? Duration.ofNanos(50_000) : Duration.ZERO;
    }

    /**
     * Makes the calling thread's next wait for a task (after the task it runs now) park at once,
     * without spinning: for a task that knows no next task is likely within the spin (a runner that
     * has just sent a large agent on, whose next stop takes longer than the spin to come back),
     * so the spin does not take a processor from the threads that have work (on two processors,
     * those of the host reading the agent). A thread of another pool that calls it is not affected.
     */
    public void parkNext() {
        parkNext.get()[0] = true;
    }

    /** @return whether the calling thread was told to park at once ({@link #parkNext}); the flag is cleared */
    private boolean parksNow() {
        boolean[] flag = parkNext.get();
        boolean park = flag[0];
        flag[0] = false;
        return park;
    }

    /** @return how many threads spin now (for tests) */
    public int spinning() {
        return spinning.get();
    }

    @Override
    public boolean offer(E e) {
        for (int n = unclaimed.get(); n > 0; n = unclaimed.get()) {
            if (unclaimed.compareAndSet(n, n - 1)) {
                slot.add(e); // a spinning thread waits for it
                return true;
            }
        }
        return parked.offer(e);
    }

    @Override
    public E poll(long timeout, TimeUnit unit) throws InterruptedException {
        long start = nanoTime.getAsLong();
        long wait = unit.toNanos(timeout);
        E e = parksNow() ? null : spin(Math.min(spinNanos, wait));
        if (e != null) {
            return e;
        }
        long left = wait - (nanoTime.getAsLong() - start);
        return left > 0 ? parked.poll(left, TimeUnit.NANOSECONDS) : null;
    }

    @Override
    public E take() throws InterruptedException {
        E e = parksNow() ? null : spin(spinNanos);
        return e != null ? e : parked.take();
    }

    /**
     * Spins up to {@code nanos} for a task (longer only while a task that claimed this thread is
     * on its way: between an offer's claim and its putting the task in the slot), if
     * {@code worthSpinning} says so. An interrupt
     * (the pool shutting down) is left set for the park that follows.
     */
    private E spin(long nanos) {
        if (nanos <= 0 || !worthSpinning.getAsBoolean()) {
            return null;
        }
        spinning.incrementAndGet();
        unclaimed.incrementAndGet();
        try {
            long until = nanoTime.getAsLong() + nanos;
            while (true) {
                E e = slot.poll();
                if (e != null) {
                    return e;
                }
                if (nanoTime.getAsLong() - until >= 0) {
                    int n = unclaimed.get();
                    if (n > 0 && unclaimed.compareAndSet(n, n - 1)) {
                        return null;
                    }
                }
                // Yield rather than only pause: on two processors a spinning thread must not keep one
                // from a thread that has work (the one that would hand it the next task).
                Thread.yield();
            }
        } finally {
            spinning.decrementAndGet();
        }
    }

    @Override
    public E poll() {
        E e = slot.poll();
        return e != null ? e : parked.poll();
    }

    @Override
    public E peek() {
        return slot.peek();
    }

    @Override
    public void put(E e) throws InterruptedException {
        throw new UnsupportedOperationException("a hand-off queue takes tasks with offer only");
    }

    @Override
    public boolean offer(E e, long timeout, TimeUnit unit) {
        return offer(e);
    }

    @Override
    public int remainingCapacity() {
        return 0;
    }

    @Override
    public boolean remove(Object o) {
        return slot.remove(o);
    }

    @Override
    public int drainTo(Collection<? super E> c) {
        return drainTo(c, Integer.MAX_VALUE);
    }

    @Override
    public int drainTo(Collection<? super E> c, int maxElements) {
        int n = 0;
        E e;
        while (n < maxElements && (e = slot.poll()) != null) {
            c.add(e);
            n++;
        }
        return n;
    }

    @Override
    public Iterator<E> iterator() {
        return slot.iterator();
    }

    @Override
    public int size() {
        return slot.size();
    }
}
