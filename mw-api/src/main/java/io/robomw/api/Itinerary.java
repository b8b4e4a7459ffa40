package io.robomw.api;

import java.io.Serializable;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Optional;

/**
 * The stops an agent visits, in order (after Aglets' {@code SeqItinerary}): each stop is a host
 * and, optionally, a {@link Task} to do there; a stop without a task runs {@link Agent#run()}. The
 * agent may change its itinerary while it travels: stops added, inserted or removed take effect
 * when it next moves on. A whole itinerary can be repeated.
 *
 * <p>When the next stop cannot be reached, the {@link UnreachablePolicy} says what happens; every
 * stop's outcome is kept in {@link #history()}, which travels with the agent and comes home with
 * it. Not thread-safe: used on the agent's own thread.
 */
public final class Itinerary implements Serializable {

    private static final long serialVersionUID = 1L;

    /** Work to do at one stop. Serializable, so lambdas given as tasks travel with the agent. */
    @FunctionalInterface
    public interface Task extends Serializable {
        /**
         * @param context the host the agent is at
         * @throws Exception if the task fails; the stop is recorded as {@link Outcome#FAILED} and the trip goes on
         */
        void execute(AgentContext context) throws Exception;
    }

    /**
     * One stop.
     *
     * @param host the agent host's address, for example {@code rmi://127.0.0.1:1099/nxt}
     * @param task what to do there, or {@code null} for {@link Agent#run()}
     */
    public record Stop(String host, Task task) implements Serializable {
        /** Checks the host is given. */
        public Stop {
            Objects.requireNonNull(host, "host");
        }
    }

    /** What to do when the next stop's host cannot be reached or refuses the agent. */
    public enum UnreachablePolicy {
        /** Go on to the stop after it (the default). */
        SKIP,
        /** Try again {@link #retries()} times, {@link #retryBackoff()} apart; then skip it. */
        RETRY,
        /** End the trip: the agent's result goes home now. */
        RETURN_HOME
    }

    /** How a stop ended. */
    public enum Outcome {
        /** Its work ran to the end. */
        DONE,
        /** Its work threw; the detail says what. */
        FAILED,
        /** Its host could not be reached, and the policy went on without it. */
        UNREACHABLE,
        /** Its host stopped (was killed) while the work ran; the work is never run twice, so it was not run again. */
        INTERRUPTED
    }

    /**
     * The outcome of one visit.
     *
     * @param round   which repetition of the itinerary, from 0
     * @param host    the stop's host
     * @param outcome how it ended
     * @param detail  why, for anything but {@link Outcome#DONE}; empty otherwise
     */
    public record Visit(int round, String host, Outcome outcome, String detail) implements Serializable {
    }

    private final ArrayList<Stop> stops = new ArrayList<>();
    private final ArrayList<Visit> history = new ArrayList<>();
    private int current = -1;
    private int round;
    private int rounds = 1;
    private UnreachablePolicy policy = UnreachablePolicy.SKIP;
    private int retries = 3;
    private long retryBackoffMillis = 500;

    /**
     * Adds a stop at the end where {@link Agent#run()} is the work.
     *
     * @param host the host's address
     * @return this itinerary
     */
    public Itinerary addStop(String host) {
        return addStop(host, null);
    }

    /**
     * Adds a stop at the end (Aglets' {@code addTask}).
     *
     * @param host the host's address
     * @param task the work there, or {@code null} for {@link Agent#run()}
     * @return this itinerary
     */
    public Itinerary addStop(String host, Task task) {
        stops.add(new Stop(host, task));
        return this;
    }

    /**
     * Inserts a stop right after the current one, so the agent goes there next.
     *
     * @param host the host's address
     * @param task the work there, or {@code null} for {@link Agent#run()}
     * @return this itinerary
     */
    public Itinerary insertNext(String host, Task task) {
        stops.add(current + 1, new Stop(host, task));
        return this;
    }

    /**
     * Removes a stop that has not been visited yet in this round.
     *
     * @param index the stop's index in {@link #stops()}
     * @return this itinerary
     * @throws IllegalArgumentException if the stop is the current one or already visited in this round
     */
    public Itinerary removeStop(int index) {
        if (index <= current || index >= stops.size()) {
            throw new IllegalArgumentException("stop " + index + " cannot be removed: only stops after the current one (" + current
                    + ") and before the end (" + stops.size() + ") can");
        }
        stops.remove(index);
        return this;
    }

    /** Removes every stop and the history, for an agent that starts a new trip. */
    public void clear() {
        stops.clear();
        history.clear();
        current = -1;
        round = 0;
    }

    /**
     * Repeats the whole itinerary: after its last stop the agent goes to the first again, until
     * it has done {@code rounds} rounds.
     *
     * @param rounds how many times to go round, at least 1
     * @return this itinerary
     */
    public Itinerary repeat(int rounds) {
        if (rounds < 1) {
            throw new IllegalArgumentException(rounds + " was supplied for rounds: rounds must be at least 1");
        }
        this.rounds = rounds;
        return this;
    }

    /**
     * @param policy what to do when a stop cannot be reached
     * @return this itinerary
     */
    public Itinerary onUnreachable(UnreachablePolicy policy) {
        this.policy = Objects.requireNonNull(policy, "policy");
        return this;
    }

    /**
     * Sets how {@link UnreachablePolicy#RETRY} retries.
     *
     * @param retries how many more attempts after the first, at least 0
     * @param backoff the wait between attempts
     * @return this itinerary
     */
    public Itinerary retry(int retries, Duration backoff) {
        if (retries < 0) {
            throw new IllegalArgumentException(retries + " was supplied for retries: retries must be at least 0");
        }
        this.retries = retries;
        this.retryBackoffMillis = backoff.toMillis();
        return this;
    }

    /**
     * Replaces this itinerary's plan (stops, rounds, unreachable policy, retries) with a copy of
     * another's; the history and position start afresh. Used for clones, which travel a plan of
     * their own.
     *
     * @param other the plan to copy
     * @return this itinerary
     */
    public Itinerary copyPlan(Itinerary other) {
        clear();
        stops.addAll(other.stops);
        rounds = other.rounds;
        policy = other.policy;
        retries = other.retries;
        retryBackoffMillis = other.retryBackoffMillis;
        return this;
    }

    /** @return how many rounds of {@link #repeat} the itinerary makes */
    public int rounds() {
        return rounds;
    }

    /** @return the stops, in order (a copy) */
    public List<Stop> stops() {
        return List.copyOf(stops);
    }

    /** @return the outcome of every visit so far, in order (a copy) */
    public List<Visit> history() {
        return List.copyOf(history);
    }

    /** @return the stop the agent is at, or empty before the trip starts and after it ends */
    public Optional<Stop> currentStop() {
        return current >= 0 && current < stops.size() ? Optional.of(stops.get(current)) : Optional.empty();
    }

    /** @return the index of the current stop in {@link #stops()}, or -1 before the trip starts */
    public int currentIndex() {
        return current;
    }

    /** @return which round of {@link #repeat} the agent is in, from 0 */
    public int round() {
        return round;
    }

    /** @return whether no stop follows the current one (Aglets' {@code atLastDestination}) */
    public boolean atLastDestination() {
        return current + 1 >= stops.size() && round + 1 >= rounds;
    }

    /** @return the policy for unreachable stops */
    public UnreachablePolicy unreachablePolicy() {
        return policy;
    }

    /** @return how many more attempts {@link UnreachablePolicy#RETRY} makes */
    public int retries() {
        return retries;
    }

    /** @return the wait between attempts */
    public Duration retryBackoff() {
        return Duration.ofMillis(retryBackoffMillis);
    }

    /**
     * Moves on to the next stop (Aglets' {@code goToNext}), going round again if {@link #repeat}
     * asks for it. Called by the agent runtime.
     *
     * @return the next stop, or empty if the trip is over
     */
    public Optional<Stop> goToNext() {
        if (current + 1 < stops.size()) {
            current++;
            return Optional.of(stops.get(current));
        }
        if (round + 1 < rounds && !stops.isEmpty()) {
            round++;
            current = 0;
            return Optional.of(stops.get(0));
        }
        current = stops.size();
        return Optional.empty();
    }

    /** @return the stop {@link #goToNext()} would move to, without moving */
    public Optional<Stop> peekNext() {
        if (current + 1 < stops.size()) {
            return Optional.of(stops.get(current + 1));
        }
        if (round + 1 < rounds && !stops.isEmpty()) {
            return Optional.of(stops.get(0));
        }
        return Optional.empty();
    }

    /**
     * Records how the visit to the current stop ended. Called by the agent runtime.
     *
     * @param host    the stop's host
     * @param outcome how it ended
     * @param detail  why, or empty
     */
    public void record(String host, Outcome outcome, String detail) {
        history.add(new Visit(round, host, outcome, detail == null ? "" : detail));
    }

    @Override
    public String toString() {
        return "Itinerary" + stops.stream().map(Stop::host).toList() + " at " + current + ", round " + round + " of " + rounds;
    }
}
