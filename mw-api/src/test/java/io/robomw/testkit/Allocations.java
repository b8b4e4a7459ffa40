package io.robomw.testkit;

import java.lang.management.ManagementFactory;

/**
 * What the calling thread allocates on the heap while it runs a step (HotSpot's per-thread allocation counter, {@code
 * com.sun.management.ThreadMXBean}): for tests that bound a hot path's garbage. Warm the step up first (the JIT's escape
 * analysis removes allocations only in compiled code), then measure over many calls: the counter's granularity is a TLAB.
 */
public final class Allocations {

    /** A step that may throw. */
    @FunctionalInterface
    public interface Step {
        /** @throws Exception whatever the step throws (the measurement fails with it) */
        void run() throws Exception;
    }

    private Allocations() {
    }

    /**
     * @param calls how many times to run the step (thousands for a step that should allocate nothing)
     * @param step  the step, run on the calling thread
     * @return the bytes the calling thread allocated per call, on average
     * @throws Exception what the step threw
     */
    public static long perCall(int calls, Step step) throws Exception {
        com.sun.management.ThreadMXBean threads = (com.sun.management.ThreadMXBean) ManagementFactory.getThreadMXBean();
        long thread = Thread.currentThread().getId();
        long before = threads.getThreadAllocatedBytes(thread);
        for (int i = 0; i < calls; i++) {
            step.run();
        }
        return (threads.getThreadAllocatedBytes(thread) - before) / calls;
    }
}
