package io.robomw.platform.motor;

import java.time.Duration;
import java.util.List;
import java.util.Objects;

/**
 * The Platform Layer of a <em>batch</em> of robots of one robot file, driven together (a swarm):
 * the motor platform and execution action thread of each member, over arrays instead of objects
 * per robot. A batch takes the one kind of command a swarm's controller sends at every tick, a
 * continuous drive on the members' motors ({@code drive(v, ω)} as the Configuration Layer turns it
 * into wheel speeds), and keeps the rules of the {@link io.robomw.platform.exec.ExecutionActionThread}
 * that apply to it, member by member:
 * <ul>
 *   <li><b>Refresh:</b> {@link #refresh} queues a member's new speeds; its next {@link #cycle}
 *   admits the last ones queued (a refresh of the running drive, or a new drive), and restarts the
 *   member's watchdog.</li>
 *   <li><b>Watchdog:</b> a drive not refreshed for longer than the batch's watchdog timeout ends at
 *   the member's next cycle, braking its motors (0 = no watchdog).</li>
 *   <li><b>Failure:</b> {@link #fail} ends a member's drive and brakes its motors (what one member's
 *   part of a step threw concerns that member only).</li>
 *   <li><b>Release:</b> {@link #release} hands a member back to a platform of its own (a robot a
 *   program addresses one by one): its drive ends, its motors brake, and the batch does not touch
 *   it again.</li>
 * </ul>
 * The speeds that changed in a member's cycle go to the {@link BatchMotorDriver} at the end of it,
 * as a robot's changed motor states go to its driver after its action thread's cycle.
 *
 * <h2>Threads</h2>
 * A member is refreshed and cycled by one thread at a time (a simulation's worker that handles it
 * in a pass; the simulation orders its passes); different members may be refreshed and cycled on
 * different threads at once: each touches only its own slots. Whoever cycles the batch owns its
 * failures: what {@link #cycle} throws concerns the member cycled, and the owner hands it to its
 * {@link io.robomw.api.spi.FailurePolicy} and calls {@link #fail}.
 */
public final class MotorBatch {

    private final String name;
    private final List<String> ports;
    private final int motors;
    private final int members;
    private final long watchdogNanos;
    private final BatchMotorDriver driver;
    /** Per member and motor: the speeds of the last refresh not admitted yet, degrees per second. */
    private final double[] queued;
    /** Per member and motor: the speeds its running drive wants (0 while none runs). */
    private final double[] wanted;
    /** Per member: when its watchdog was last restarted (its drive admitted or refreshed), clock nanoseconds. */
    private final long[] refreshedAt;
    /**
     * Per member: {@link #IDLE}, {@link #QUEUED}, {@link #RUNNING}, {@link #RUNNING_QUEUED} or {@link #RELEASED}: a byte
     * a member in one array the cycle walks in order (an enum constant a member would be a reference to follow, 4-8
     * bytes of a 100,000-member array). In memory only: never written to a wire or a file.
     */
    private final byte[] state;

    private static final byte IDLE = 0;
    private static final byte QUEUED = 1;
    private static final byte RUNNING = 2;
    private static final byte RUNNING_QUEUED = 3;
    private static final byte RELEASED = 4;

    /**
     * @param name     the batch's name (its robot file's), for messages
     * @param ports    every member's motor ports, in the order speeds are given (a drive's left and right wheel)
     * @param members  how many robots it drives
     * @param watchdog how long a drive runs without a refresh before it ends; {@link Duration#ZERO}: no watchdog
     * @param driver   the members' hardware face
     */
    public MotorBatch(String name, List<String> ports, int members, Duration watchdog, BatchMotorDriver driver) {
        this.name = Objects.requireNonNull(name, "name");
        this.ports = List.copyOf(ports);
        if (this.ports.isEmpty()) {
            throw new IllegalArgumentException("batch '" + name + "': a batch drives one motor or more a member, got none");
        }
        if (members < 0) {
            throw new IllegalArgumentException("batch '" + name + "': members must be >= 0, got " + members);
        }
        if (watchdog.isNegative()) {
            throw new IllegalArgumentException("batch '" + name + "': watchdog must be >= 0, got " + watchdog);
        }
        this.motors = this.ports.size();
        this.members = members;
        this.watchdogNanos = watchdog.toNanos();
        this.driver = Objects.requireNonNull(driver, "driver");
        this.queued = new double[members * motors];
        this.wanted = new double[members * motors];
        this.refreshedAt = new long[members];
        this.state = new byte[members];
    }

    /** @return the batch's name */
    public String name() {
        return name;
    }

    /** @return every member's motor ports, in the order speeds are given */
    public List<String> ports() {
        return ports;
    }

    /** @return how many robots it drives */
    public int members() {
        return members;
    }

    /**
     * Queues a member's new speeds for its next cycle (the newest queued before a cycle wins, as a
     * refresh slot's): the drive command of a member with two motors, without an array.
     *
     * @param member the member
     * @param first  its first motor's speed, degrees per second
     * @param second its second motor's speed
     * @throws IllegalArgumentException if the batch's members have other than two motors
     * @throws IllegalStateException    if the member was {@linkplain #release released}
     */
    public void refresh(int member, double first, double second) {
        if (motors != 2) {
            throw new IllegalArgumentException("batch '" + name + "' drives " + motors + " motors a member, got 2 speeds");
        }
        byte s = state[member];
        if (s == RELEASED) {
            throw releasedError(member);
        }
        queued[2 * member] = first;
        queued[2 * member + 1] = second;
        state[member] = s == RUNNING || s == RUNNING_QUEUED ? RUNNING_QUEUED : QUEUED;
    }

    /**
     * One cycle of a member, in the execution action thread's order: admit its queued speeds (a
     * new drive, or a refresh of the running one: the watchdog restarts), else end its drive if the
     * watchdog expired (its motors brake); then hand the speeds that changed to the driver.
     *
     * @param member the member
     * @param now    the clock's time, nanoseconds
     */
    public void cycle(int member, long now) {
        byte s = state[member];
        int from = member * motors;
        boolean changed = false;
        if (s == QUEUED || s == RUNNING_QUEUED) {
            for (int k = from; k < from + motors; k++) {
                if (Double.compare(wanted[k], queued[k]) != 0) {
                    wanted[k] = queued[k];
                    changed = true;
                }
            }
            refreshedAt[member] = now;
            // a drive that starts is sent whole, as a new container's action sets its states
            changed |= s == QUEUED;
            state[member] = RUNNING;
        } else if (s == RUNNING && watchdogNanos > 0 && now - refreshedAt[member] > watchdogNanos) {
            changed = brake(member);
            state[member] = IDLE;
        } else {
            return;
        }
        if (changed) {
            driver.send(member, wanted, from);
        }
    }

    /**
     * Ends a member's drive after a failure of its part of a step (reported by whoever cycles the
     * batch): its motors brake. A released member is left alone.
     *
     * @param member the member
     */
    public void fail(int member) {
        if (state[member] == RELEASED) {
            return;
        }
        state[member] = IDLE;
        brake(member);
        driver.send(member, wanted, member * motors);
    }

    /**
     * Hands a member back to a platform of its own: its drive ends, its motors brake, and the batch
     * neither refreshes nor cycles it again. On the thread that cycles the batch, between cycles.
     *
     * @param member the member
     */
    public void release(int member) {
        if (state[member] == RELEASED) {
            return;
        }
        fail(member);
        state[member] = RELEASED;
    }

    /**
     * @param member the member
     * @return whether it was {@linkplain #release released}
     */
    public boolean released(int member) {
        return state[member] == RELEASED;
    }

    /**
     * @param member the member
     * @return whether a drive runs on it (admitted, and neither ended by its watchdog nor failed)
     */
    public boolean running(int member) {
        byte s = state[member];
        return s == RUNNING || s == RUNNING_QUEUED;
    }

    /**
     * @param member the member
     * @param motor  one of its motors, by its place in {@link #ports()}
     * @return the speed its running drive wants, degrees per second (0 while none runs)
     */
    public double wanted(int member, int motor) {
        return wanted[member * motors + motor];
    }

    /**
     * @param member the member
     * @param motor  one of its motors, by its place in {@link #ports()}
     * @return the motor's encoder now, degrees
     */
    public double degrees(int member, int motor) {
        return driver.degrees(member, motor);
    }

    /** Wants a member's motors stopped; @return whether that changed anything. */
    private boolean brake(int member) {
        boolean changed = false;
        for (int k = member * motors; k < (member + 1) * motors; k++) {
            changed |= wanted[k] != 0;
            wanted[k] = 0;
        }
        return changed;
    }

    private IllegalStateException releasedError(int member) {
        return new IllegalStateException("batch '" + name + "': member " + member
                + " was released to a platform of its own; drive it through its robot, not through the batch");
    }
}
