package io.robomw.platform.ft.intelligent;

/**
 * Where a motor's impulse wheel stands, in ticks (switch transitions), from the switch read at
 * each poll and how long the motor was on in between.
 *
 * <h2>Why not just count</h2>
 * A poll shows the switch's state, so between two polls it tells only whether the switch changed
 * an odd or an even number of times; a count alone loses every pair of transitions a late poll
 * missed, and places the wheel somewhere within a tick (11 mm of travel on the robots here). This
 * counter keeps the set of positions that both the switch and the motor's on-time allow:
 * <ul>
 *   <li>the edges between ticks lie at whole numbers; the wheel is in the tick interval the
 *   switch's transitions put it in;</li>
 *   <li>each poll moves the set by the travel the on-time allows: at least {@link #SLOWEST} and
 *   at most all of full speed ({@code ticksPerSecondAtFullPower}) times the least and the most the
 *   motor can have been on (the poll's exchange times bound when the interface took each
 *   command); of the tick intervals the switch's parity allows, it then takes the one the moved
 *   set overlaps most (of those it overlaps alike, the nearest to the set's middle; the nearest if
 *   it overlaps none), and keeps the set within it. A late poll (a loaded
 *   host) after the motor passed two or more edges thus counts them, and a transition narrows the
 *   set to just past its edge;</li>
 *   <li>while the motor is off only the switch moves the wheel: edges are crossed in the
 *   direction the motor last turned;</li>
 *   <li>at the start the wheel's phase is unknown: anywhere in its first tick.</li>
 * </ul>
 * The position reported is the middle of the set.
 *
 * <p>Not thread-safe: the link thread owns it.
 */
final class ImpulseCounter {

    /**
     * The least fraction of full speed a motor that is on turns at: it takes a moment to get up
     * to speed, and a loaded one turns slower.
     */
    static final double SLOWEST = 0.85;

    /** Overlaps within this many ticks count as equal: the on-time allows each as much. */
    private static final double OVERLAP_EPSILON = 0.05;

    private final double ticksPerSecondAtFullPower;
    /** The lower edge of the tick interval the wheel is in. */
    private long lower;
    /** The positions it can be at, within [lower, lower + 1]. */
    private double least;
    private double most = 1;
    private long recovered;

    /**
     * @param ticksPerRevolution          switch transitions per motor turn
     * @param degreesPerSecondAtFullPower the motor's speed when on
     */
    ImpulseCounter(int ticksPerRevolution, double degreesPerSecondAtFullPower) {
        if (ticksPerRevolution <= 0) {
            throw new IllegalArgumentException("ticksPerRevolution must be > 0, got " + ticksPerRevolution);
        }
        this.ticksPerSecondAtFullPower = degreesPerSecondAtFullPower * ticksPerRevolution / 360.0;
    }

    /**
     * Takes one poll.
     *
     * @param switchChanged  whether the switch differs from the last poll
     * @param driven         the direction the motor was driven in since the last poll: 1, -1, or 0 (off)
     * @param coasting       the direction it last turned, for a motor that was off
     * @param leastOnSeconds the least time it can have been driven since the last poll
     * @param mostOnSeconds  the most time it can have been driven since the last poll
     */
    void poll(boolean switchChanged, int driven, int coasting, double leastOnSeconds, double mostOnSeconds) {
        int parity = switchChanged ? 1 : 0;
        if (driven == 0) {
            if (parity == 1) {
                int direction = coasting >= 0 ? 1 : -1;
                lower += direction;
                least = direction > 0 ? lower : lower + 1;
                most = least;
            }
            return;
        }
        double shortest = Math.max(0, leastOnSeconds) * SLOWEST * ticksPerSecondAtFullPower;
        double longest = Math.max(0, mostOnSeconds) * ticksPerSecondAtFullPower;
        double from = driven > 0 ? least + shortest : least - longest;
        double to = driven > 0 ? most + longest : most - shortest;
        // The best guess of where it went: the middle of what the on-time allows.
        double middle = (from + to) / 2;
        int best = parity;
        double bestOverlap = -Double.MAX_VALUE;
        double bestDistance = Double.MAX_VALUE;
        for (int k = parity; k <= parity + 2 + Math.ceil(longest); k += 2) {
            long edge = lower + (long) driven * k;
            double overlap = Math.min(Math.min(to, edge + 1) - Math.max(from, edge), 1);
            double distance = Math.abs(middle - (edge + 0.5));
            boolean better = overlap > bestOverlap + OVERLAP_EPSILON
                    || (overlap > bestOverlap - OVERLAP_EPSILON && distance < bestDistance);
            if (better) {
                best = k;
                bestOverlap = overlap;
                bestDistance = distance;
            }
        }
        if (best > parity) {
            recovered += best - parity;
        }
        lower += (long) driven * best;
        if (bestOverlap >= 0) {
            least = Math.max(from, lower);
            most = Math.min(to, lower + 1);
        } else {
            // The switch and the on-time disagree (the motor was slower or faster than allowed):
            // believe the switch, at the side of the interval nearest the estimate.
            double nearest = to < lower ? lower : lower + 1;
            least = nearest;
            most = nearest;
        }
    }

    /** @return the position, ticks: the middle of the positions the wheel can be at */
    double ticks() {
        return (least + most) / 2;
    }

    /** @return transitions counted beyond what the switch's parity showed, because polls came late */
    long recovered() {
        return recovered;
    }
}
