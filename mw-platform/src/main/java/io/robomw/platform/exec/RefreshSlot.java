package io.robomw.platform.exec;

import io.robomw.api.spi.CommandPriority;

import java.util.Arrays;
import java.util.Objects;
import java.util.Set;

/**
 * A continuous command that its submitter refreshes again and again with new values (a robot's
 * {@code drive}, ten times a second), without a new container each time: the values go into this
 * slot, which waits in the {@link ExecutionActionThread}'s queue like a container and is admitted
 * by the same rules, in its place among the other commands.
 *
 * <h2>What a refresh does</h2>
 * {@link ExecutionActionThread#refresh(RefreshSlot, double[])} puts the values in the slot:
 * <ul>
 *   <li>if the slot is not queued, it is queued behind everything submitted before;</li>
 *   <li>if it is queued and nothing was submitted after it, its values are replaced (the newest
 *   refresh is what the cycle admits, as the last of several refreshes queued together would
 *   have set it);</li>
 *   <li>if it is queued but something was submitted after it (a move, a stop), the new values go
 *   as a container of their own ({@link Handler#container}) behind that, so a command submitted
 *   between two refreshes is admitted between them, as it would be with a container per refresh.</li>
 * </ul>
 * When the cycle reaches the slot, a running container that holds its actuators and is
 * {@linkplain Container.Builder#refreshes refreshed} by its key, actuators and priority is
 * refreshed in place ({@link Handler#refresh}: it sets the new values, the watchdog restarts);
 * otherwise the values become a new container ({@link Handler#container}) admitted by the clash
 * rules, exactly as a submitted one. Nobody waits for a refresh: what becomes of it (refused,
 * interrupted later, failed) is logged and counted as for a container, and reaches callers through
 * the futures of the containers it started or refreshed.
 *
 * <p>A slot belongs to one execution action thread, from its first refresh on. Values are copied:
 * the caller may reuse its array.
 */
public final class RefreshSlot {

    /** What the slot's values do, on the cycling thread. */
    public interface Handler {
        /**
         * Refreshes the running container this slot's key, actuators and priority match, with new
         * values; the watchdog has been restarted. Must not block.
         *
         * @param values   the values (the slot's own array: read them now, do not keep it)
         * @param nowNanos the action thread's clock at the start of this cycle
         */
        void refresh(double[] values, long nowNanos);

        /**
         * @param values the values (the slot's own array: copy what the container keeps)
         * @return a new container that runs these values, for when no running container can be
         *         refreshed; it must carry the slot's refresh key, actuators and priority
         */
        Container container(double[] values);
    }

    private final String name;
    private final Set<String> requirements;
    private final CommandPriority priority;
    private final String refreshKey;
    private final Handler handler;
    // Guarded by the owner's monitor (the ExecutionActionThread object):
    private final double[] pending;
    /** Its place in the owner's queue while queued ({@link #queued}). */
    long ticket;
    boolean queued;
    /** Set by {@link #retire()}; the owner forgets a retired slot that is not queued. */
    volatile boolean retired;
    // Cycling thread only:
    final double[] taken;
    /** The requirements as an array, which each admission walks without an iterator. */
    final String[] actuators;
    /** The execution action thread it belongs to, from its first refresh (under that thread's monitor). */
    ExecutionActionThread owner;

    /**
     * @param name         the command's name, for logs and errors
     * @param requirements the actuators it needs (an unmodifiable set; give the same set instance
     *                     as the containers it refreshes, so they compare at a glance)
     * @param priority     its priority
     * @param refreshKey   the refresh key of the containers it refreshes
     * @param size         how many values a refresh carries
     * @param handler      what the values do
     */
    public RefreshSlot(String name, Set<String> requirements, CommandPriority priority, String refreshKey, int size, Handler handler) {
        this.name = Objects.requireNonNull(name, "name");
        if (requirements.isEmpty()) {
            throw new IllegalArgumentException("refresh slot '" + name + "' requires no actuator; every command must name the actuators it drives");
        }
        this.requirements = Set.copyOf(requirements);
        this.actuators = this.requirements.toArray(String[]::new);
        this.priority = Objects.requireNonNull(priority, "priority");
        this.refreshKey = Objects.requireNonNull(refreshKey, "refreshKey");
        this.handler = Objects.requireNonNull(handler, "handler");
        this.pending = new double[size];
        this.taken = new double[size];
    }

    /** @return the command's name */
    public String name() {
        return name;
    }

    /** @return the actuators it needs */
    public Set<String> requirements() {
        return requirements;
    }

    /** @return its priority */
    public CommandPriority priority() {
        return priority;
    }

    /** @return the refresh key of the containers it refreshes */
    public String refreshKey() {
        return refreshKey;
    }

    /** @return how many values a refresh carries */
    public int size() {
        return pending.length;
    }

    /**
     * Says the submitter has replaced this slot by another (its command's name, actuators or
     * watchdog changed): once its last queued values have been admitted, the thread forgets it.
     */
    public void retire() {
        retired = true;
    }

    Handler handler() {
        return handler;
    }

    /** Copies values in; under the owner's lock. */
    void put(double[] values) {
        System.arraycopy(values, 0, pending, 0, pending.length);
    }

    /** Puts two values in (a slot of two, a drive's wheels); under the owner's lock. */
    void put(double first, double second) {
        pending[0] = first;
        pending[1] = second;
    }

    /** Takes the queued values for the cycle; under the owner's lock. */
    void take() {
        System.arraycopy(pending, 0, taken, 0, pending.length);
        queued = false;
    }

    @Override
    public String toString() {
        return "RefreshSlot[" + name + " " + requirements + " " + priority + (queued ? " queued " + Arrays.toString(pending) : "") + "]";
    }
}
