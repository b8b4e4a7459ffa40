package io.robomw.platform;

/** Where a {@link BrickPlatform} runs its motor platform's link side. */
public enum LinkThreading {
    /**
     * On a named link thread of its own, paced by the cycle: for bricks behind serial or TCP
     * links, so the execution action thread never waits for I/O.
     */
    OWN_THREAD,
    /**
     * On the cycling thread right after each cycle: for platforms without I/O (the simulator),
     * which keeps a simulated run exactly repeatable.
     */
    INLINE
}
