package io.robomw.api.spi;

/**
 * Who runs a platform's cycles: said explicitly when a platform is opened, never guessed from its
 * clock (a decorated wall clock is still a wall clock).
 */
public enum Cycling {
    /**
     * The platform's own named threads (its execution action thread, its link's owner), paced by
     * its clock: a robot on real hardware, or on an emulator in real time.
     */
    OWN_THREADS,
    /**
     * Its owner calls the cycles (a simulation stepping its world and every robot in it, so that a
     * run is repeatable): the platform starts no thread of its own.
     */
    BY_OWNER
}
