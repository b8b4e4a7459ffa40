package io.robomw.api;

import java.io.IOException;
import java.io.InvalidObjectException;
import java.io.ObjectInputStream;
import java.io.ObjectOutputStream;
import java.io.ObjectStreamField;
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

    private static final long serialVersionUID = 2L;
    /** Nothing by default: {@link #writeObject} writes the itinerary compactly. */
    private static final ObjectStreamField[] serialPersistentFields = {};

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

    /**
     * What to do when the next stop's host cannot be reached or refuses the agent. Each policy
     * travels as its {@code code} (see {@link Itinerary}'s serial form), never as its position here.
     */
    public enum UnreachablePolicy {
        /** Go on to the stop after it (the default). Code 0. */
        SKIP(0),
        /** Try again {@link #retries()} times, {@link #retryBackoff()} apart; then skip it. Code 1. */
        RETRY(1),
        /** End the trip: the agent's result goes home now. Code 2. */
        RETURN_HOME(2);

        private final int code;

        UnreachablePolicy(int code) {
            this.code = code;
        }

        /** @return the policy's code in the serial form */
        int code() {
            return code;
        }

        /**
         * @param code a code read from the serial form
         * @return its policy
         * @throws InvalidObjectException if no policy has that code
         */
        static UnreachablePolicy fromCode(int code) throws InvalidObjectException {
            for (UnreachablePolicy p : values()) {
                if (p.code == code) {
                    return p;
                }
            }
            throw new InvalidObjectException("unknown unreachable-policy code " + code + " in an itinerary (known: " + known(values(), UnreachablePolicy::code) + ")");
        }
    }

    /**
     * How a stop ended. Each outcome travels as its {@code code} (see {@link Itinerary}'s serial
     * form), never as its position here.
     */
    public enum Outcome {
        /** Its work ran to the end. Code 0. */
        DONE(0),
        /** Its work threw; the detail says what. Code 1. */
        FAILED(1),
        /** Its host could not be reached, and the policy went on without it. Code 2. */
        UNREACHABLE(2),
        /** Its host stopped (was killed) while the work ran; the work is never run twice, so it was not run again. Code 3. */
        INTERRUPTED(3);

        private final int code;

        Outcome(int code) {
            this.code = code;
        }

        /** @return the outcome's code in the serial form */
        int code() {
            return code;
        }

        /**
         * @param code a code read from the serial form
         * @return its outcome
         * @throws InvalidObjectException if no outcome has that code
         */
        static Outcome fromCode(int code) throws InvalidObjectException {
            Outcome o = lookup(code);
            if (o == null) {
                throw new InvalidObjectException(unknown(code));
            }
            return o;
        }

        /** @return the outcome of a code, or {@code null} if none has it */
        static Outcome lookup(int code) {
            for (Outcome o : values()) {
                if (o.code == code) {
                    return o;
                }
            }
            return null;
        }

        static String unknown(int code) {
            return "unknown visit-outcome code " + code + " in an itinerary (known: " + known(values(), Outcome::code) + ")";
        }
    }

    /** The codes of an enum's constants as an error message lists them: "0 A, 1 B, ...". Each code is written once, in its constant. */
    private static <E extends Enum<E>> String known(E[] constants, java.util.function.ToIntFunction<E> code) {
        StringBuilder b = new StringBuilder();
        for (E e : constants) {
            if (b.length() > 0) {
                b.append(", ");
            }
            b.append(code.applyAsInt(e)).append(' ').append(e.name());
        }
        return b.toString();
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

    private ArrayList<Stop> stops = new ArrayList<>();
    private ArrayList<Visit> history = new ArrayList<>();
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

    /**
     * Writes the itinerary by hand instead of as lists of records and enums: it travels with its
     * agent on every hop, and those classes' descriptors were most of a small agent's state and
     * of the time to read it.
     *
     * @serialData the position ({@code current}, {@code round}, {@code rounds}: ints), the
     * unreachable policy's code (byte), the retries (int) and back-off (long, milliseconds);
     * the number of stops (int), then each stop's host (a {@code String} object) and task (an
     * object, or null); the number of visits (int), then each visit's round (int), host
     * ({@code String} object), outcome code (byte) and detail ({@code String} object). The codes
     * (the values they had as ordinals before they were made explicit, so the form is unchanged):
     * <table>
     * <caption>Codes in an itinerary's serial form</caption>
     * <tr><th>code</th><th>{@link UnreachablePolicy}</th><th>{@link Outcome}</th></tr>
     * <tr><td>0</td><td>{@code SKIP}</td><td>{@code DONE}</td></tr>
     * <tr><td>1</td><td>{@code RETRY}</td><td>{@code FAILED}</td></tr>
     * <tr><td>2</td><td>{@code RETURN_HOME}</td><td>{@code UNREACHABLE}</td></tr>
     * <tr><td>3</td><td></td><td>{@code INTERRUPTED}</td></tr>
     * </table>
     * An unknown code fails the read with an {@link InvalidObjectException} naming it.
     */
    private void writeObject(ObjectOutputStream out) throws IOException {
        out.defaultWriteObject();
        out.writeInt(current);
        out.writeInt(round);
        out.writeInt(rounds);
        out.writeByte(policy.code());
        out.writeInt(retries);
        out.writeLong(retryBackoffMillis);
        out.writeInt(stops.size());
        for (Stop s : stops) {
            out.writeObject(s.host());
            out.writeObject(s.task());
        }
        out.writeInt(history.size());
        for (Visit v : history) {
            out.writeInt(v.round());
            out.writeObject(v.host());
            out.writeByte(v.outcome().code());
            out.writeObject(v.detail());
        }
    }

    /**
     * Reads what {@link #writeObject} wrote, and checks it as the public methods would. The codes
     * and settings are checked once all of this itinerary's data has been read: an exception
     * thrown with data left unread would reach the caller as the stream's "unread block data"
     * instead of the reason.
     */
    private void readObject(ObjectInputStream in) throws IOException, ClassNotFoundException {
        in.defaultReadObject();
        int cur = in.readInt();
        int rnd = in.readInt();
        int rnds = in.readInt();
        int pol = in.readUnsignedByte();
        int tries = in.readInt();
        long backoff = in.readLong();
        ArrayList<Stop> readStops = new ArrayList<>();
        for (int i = count(in); i > 0; i--) {
            String host = string(in.readObject());
            Object task = in.readObject();
            if (host == null || (task != null && !(task instanceof Task))) {
                throw new InvalidObjectException("itinerary stop with host " + host + " and task of " + (task == null ? null : task.getClass()));
            }
            readStops.add(new Stop(host, (Task) task));
        }
        ArrayList<Visit> readHistory = new ArrayList<>();
        String badVisit = null;
        for (int i = count(in); i > 0; i--) {
            int visitRound = in.readInt();
            String host = string(in.readObject());
            int code = in.readUnsignedByte();
            String detail = string(in.readObject());
            Outcome outcome = Outcome.lookup(code);
            if (badVisit == null && (host == null || detail == null || outcome == null)) {
                badVisit = outcome == null ? Outcome.unknown(code) : "malformed itinerary visit (" + host + ", outcome " + code + ")";
            }
            readHistory.add(new Visit(visitRound, host, outcome, detail));
        }
        if (badVisit != null) {
            throw new InvalidObjectException(badVisit);
        }
        UnreachablePolicy readPolicy = UnreachablePolicy.fromCode(pol);
        if (rnds < 1 || rnd < 0 || rnd >= rnds || tries < 0 || backoff < 0) {
            throw new InvalidObjectException("itinerary settings out of range: round " + rnd + " of " + rnds + ", policy " + pol + ", retries " + tries
                    + ", back-off " + backoff);
        }
        if (cur < -1 || cur > readStops.size()) {
            throw new InvalidObjectException("itinerary position " + cur + " outside its " + readStops.size() + " stops");
        }
        stops = readStops;
        history = readHistory;
        current = cur;
        round = rnd;
        rounds = rnds;
        policy = readPolicy;
        retries = tries;
        retryBackoffMillis = backoff;
    }

    private static int count(ObjectInputStream in) throws IOException {
        int n = in.readInt();
        if (n < 0) {
            throw new InvalidObjectException("negative count " + n + " in an itinerary");
        }
        return n;
    }

    private static String string(Object o) throws InvalidObjectException {
        if (o != null && !(o instanceof String)) {
            throw new InvalidObjectException("expected a string in an itinerary, found a " + o.getClass().getName());
        }
        return (String) o;
    }

    @Override
    public String toString() {
        return "Itinerary" + stops.stream().map(Stop::host).toList() + " at " + current + ", round " + round + " of " + rounds;
    }
}
