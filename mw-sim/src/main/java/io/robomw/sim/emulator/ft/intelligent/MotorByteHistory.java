package io.robomw.sim.emulator.ft.intelligent;

import io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram;

import java.util.ArrayDeque;
import java.util.Deque;
import java.util.Iterator;

/**
 * The Intelligent Interface's motor byte over wall-clock time: each command sets it at the moment
 * it arrives, and the watchdog clears it {@link IntelligentInterfaceTelegram#WATCHDOG_MILLIS} after
 * the last command. The interface's motors run in real time whatever the host does, so the
 * emulator answers and moves its simulated wheels from this record, by wall-clock time, rather
 * than from the byte in force when its (possibly held-up) simulation thread happens to step.
 *
 * <p>Entries older than {@link #KEEP_NANOS} are dropped. Not thread-safe: the emulator guards it
 * with its firmware lock.
 */
final class MotorByteHistory {

    /** How long the record reaches back. */
    static final long KEEP_NANOS = 5_000_000_000L;
    private static final long WATCHDOG_NANOS = IntelligentInterfaceTelegram.WATCHDOG_MILLIS * 1_000_000L;

    private final Deque<Command> commands = new ArrayDeque<>();
    private long trips;

    /** A motor byte and when it arrived. */
    private record Command(long atNanos, int motorByte) {
    }

    /**
     * Records a command.
     *
     * @param atNanos   when it arrived
     * @param motorByte its motor byte
     */
    void command(long atNanos, int motorByte) {
        Command last = commands.peekLast();
        if (last != null && last.motorByte() != 0 && atNanos - last.atNanos() > WATCHDOG_NANOS) {
            trips++;
        }
        commands.add(new Command(atNanos, motorByte));
        while (commands.size() > 2 && commands.peekFirst().atNanos() < atNanos - KEEP_NANOS) {
            commands.pollFirst();
        }
    }

    /**
     * @param atNanos a wall-clock time
     * @return the motor byte in force then: the last command's, or 0 once the watchdog has fired
     */
    int at(long atNanos) {
        Command in = null;
        for (Command c : commands) {
            if (c.atNanos() > atNanos) {
                break;
            }
            in = c;
        }
        if (in == null || atNanos - in.atNanos() > WATCHDOG_NANOS) {
            return 0;
        }
        return in.motorByte();
    }

    /**
     * How long, within a wall-clock interval, a motor was driven each way.
     *
     * @param motor 0..3
     * @param from  the interval's start
     * @param to    its end
     * @return seconds clockwise minus seconds counter-clockwise
     */
    double signedOnSeconds(int motor, long from, long to) {
        if (to <= from) {
            return 0;
        }
        double seconds = 0;
        Iterator<Command> it = commands.iterator();
        Command current = null;
        Command next = it.hasNext() ? it.next() : null;
        while (next != null && next.atNanos() <= from) {
            current = next;
            next = it.hasNext() ? it.next() : null;
        }
        long t = from;
        while (t < to) {
            long end = next == null ? to : Math.min(to, next.atNanos());
            seconds += direction(current, motor) * overlapWithinWatchdog(current, t, end) / 1e9;
            t = end;
            current = next;
            next = next != null && it.hasNext() ? it.next() : null;
        }
        return seconds;
    }

    private static int direction(Command c, int motor) {
        if (c == null) {
            return 0;
        }
        int d = IntelligentInterfaceTelegram.direction(c.motorByte(), motor);
        return d == IntelligentInterfaceTelegram.CW ? 1 : d == IntelligentInterfaceTelegram.CCW ? -1 : 0;
    }

    /** The part of [from, to) before the command's watchdog fired. */
    private static long overlapWithinWatchdog(Command c, long from, long to) {
        if (c == null) {
            return 0;
        }
        long until = Math.min(to, c.atNanos() + WATCHDOG_NANOS);
        return Math.max(0, until - from);
    }

    /**
     * @param now the time now
     * @return how often the watchdog switched motors off for want of commands, up to now
     */
    long watchdogTrips(long now) {
        Command last = commands.peekLast();
        boolean pending = last != null && last.motorByte() != 0 && now - last.atNanos() > WATCHDOG_NANOS;
        return trips + (pending ? 1 : 0);
    }
}
