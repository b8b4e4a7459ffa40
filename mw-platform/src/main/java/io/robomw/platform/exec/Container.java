package io.robomw.platform.exec;

import io.robomw.api.spi.CommandPriority;

import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.CompletableFuture;

/**
 * One command in the execution action thread: the actuators it requires, action objects run when
 * it starts, logic objects evaluated each cycle until all hold, and an end action run when it
 * finishes or is interrupted. Its {@link #completion()} future tells the caller how it ended.
 *
 * <p>Build with {@link #builder(String)}. Once submitted, a container is touched only by the
 * action thread.
 */
public final class Container {

    private final String name;
    private final Set<String> requirements;
    private final CommandPriority priority;
    private final InterruptionBehavior interruptionBehavior;
    // The first action and logic object in fields of their own, the rest (rarely any) in arrays: a
    // cycle of a robot's running drive reads its one logic object without another object to fetch.
    private final ActionObject firstAction;
    private final ActionObject[] moreActions;
    private final LogicObject firstLogic;
    private final LogicObject[] moreLogic;
    private final EndAction endAction;
    private final long watchdogNanos;
    private final String refreshKey;
    private final CompletableFuture<Void> completion = new CompletableFuture<>();

    /** Which logic objects have held, bit i for the i-th (the first 64). */
    private long satisfiedBits;
    /** The same for logic objects past the 64th, if there are any. */
    private boolean[] satisfiedMore;
    private long startedAt;
    /** Its place in the action thread's queue (set when submitted, under the queue's lock). */
    long ticket;
    /** The cycle that admitted it (set by the cycling thread): a refusal names the cycles it concerns. */
    long admittedIn;

    private Container(Builder b) {
        this.name = b.name;
        this.requirements = b.requirementSet != null ? b.requirementSet : immutable(b.requirements);
        List<ActionObject> actions = b.actions == null ? List.of() : b.actions;
        List<LogicObject> logic = b.logic == null ? List.of() : b.logic;
        this.priority = b.priority;
        this.interruptionBehavior = b.interruptionBehavior;
        this.firstAction = actions.isEmpty() ? null : actions.get(0);
        this.moreActions = actions.size() <= 1 ? NO_ACTIONS : actions.subList(1, actions.size()).toArray(NO_ACTIONS);
        this.firstLogic = logic.isEmpty() ? null : logic.get(0);
        this.moreLogic = logic.size() <= 1 ? NO_LOGIC : logic.subList(1, logic.size()).toArray(NO_LOGIC);
        this.endAction = b.endAction;
        this.watchdogNanos = b.watchdog.toNanos();
        this.refreshKey = b.refreshKey;
    }

    private static final ActionObject[] NO_ACTIONS = new ActionObject[0];
    private static final LogicObject[] NO_LOGIC = new LogicObject[0];

    /** {@link Set#copyOf}, without the intermediate hash set it makes, for the one or two actuators most containers need. */
    private static Set<String> immutable(java.util.LinkedHashSet<String> s) {
        if (s == null || s.isEmpty()) {
            return Set.of();
        }
        if (s.size() == 1) {
            return Set.of(s.iterator().next());
        }
        if (s.size() == 2) {
            java.util.Iterator<String> i = s.iterator();
            return Set.of(i.next(), i.next());
        }
        return Set.copyOf(s);
    }

    /**
     * @param name the container's name, used in logs and in errors given to callers
     * @return a builder
     */
    public static Builder builder(String name) {
        return new Builder(name);
    }

    /** @return its name */
    public String name() {
        return name;
    }

    /** @return the actuators it requires */
    public Set<String> requirements() {
        return requirements;
    }

    /** @return its priority */
    public CommandPriority priority() {
        return priority;
    }

    /** @return what a same-priority newcomer does to it */
    public InterruptionBehavior interruptionBehavior() {
        return interruptionBehavior;
    }

    /** @return completes when it finishes; fails when it is interrupted, refused or fails */
    public CompletableFuture<Void> completion() {
        return completion;
    }

    /**
     * @param newer a container that may refresh this one
     * @return whether {@code newer} is a refresh of this running container: the same refresh key,
     *         actuators and priority
     */
    boolean refreshedBy(Container newer) {
        return refreshKey != null && refreshKey.equals(newer.refreshKey)
                && (requirements == newer.requirements || requirements.equals(newer.requirements)) && priority == newer.priority;
    }

    /**
     * @return whether a {@link RefreshSlot} with this key, these actuators and this priority
     *         refreshes this running container (as {@link #refreshedBy(Container)} decides for a container)
     */
    boolean refreshedBy(String key, Set<String> actuators, CommandPriority p) {
        return refreshKey != null && refreshKey.equals(key)
                && (requirements == actuators || requirements.equals(actuators)) && priority == p;
    }

    /** Restarts the watchdog, for a refresh through a slot (whose handler then sets the new values). */
    void restartWatchdog(long now) {
        startedAt = now;
    }

    /** Takes over a newer container's actions and restarts the watchdog. */
    void refresh(long now, Container newer) {
        startedAt = now;
        newer.runActions(now);
    }

    void start(long now) {
        startedAt = now;
        satisfiedBits = 0;
        if (moreLogic.length >= 64) {
            satisfiedMore = new boolean[moreLogic.length + 1];
        }
        runActions(now);
    }

    /** Runs its action objects, in the order they were added. */
    private void runActions(long now) {
        if (firstAction != null) {
            firstAction.start(now);
            for (ActionObject a : moreActions) {
                a.start(now);
            }
        }
    }

    /** @return whether every logic object now holds */
    boolean evaluate(long now) {
        if (firstLogic == null) {
            return true;
        }
        boolean all = true;
        int count = moreLogic.length + 1;
        for (int i = 0; i < count; i++) {
            if (!satisfied(i)) {
                boolean holds = (i == 0 ? firstLogic : moreLogic[i - 1]).evaluate(now);
                if (holds) {
                    setSatisfied(i);
                }
                all &= holds;
            }
        }
        return all;
    }

    private boolean satisfied(int i) {
        return i < 64 ? (satisfiedBits & (1L << i)) != 0 : satisfiedMore[i];
    }

    private void setSatisfied(int i) {
        if (i < 64) {
            satisfiedBits |= 1L << i;
        } else {
            satisfiedMore[i] = true;
        }
    }

    boolean watchdogExpired(long now) {
        return watchdogNanos > 0 && now - startedAt > watchdogNanos;
    }

    Duration watchdog() {
        return Duration.ofNanos(watchdogNanos);
    }

    void end(boolean interrupted) {
        endAction.end(interrupted);
    }

    @Override
    public String toString() {
        return "Container[" + name + " " + requirements + " " + priority + "]";
    }

    /** What a container does when it ends. */
    @FunctionalInterface
    public interface EndAction {
        /**
         * @param interrupted whether it ended before its logic held
         */
        void end(boolean interrupted);
    }

    /** Builds a container. */
    public static final class Builder {
        private final String name;
        // Made when first needed: a motor platform's drive gives one set, one action and one logic object.
        private java.util.LinkedHashSet<String> requirements;
        /** The requirements as one unmodifiable set given whole (a motor platform's cached set), while nothing else was required. */
        private Set<String> requirementSet;
        private CommandPriority priority = CommandPriority.NORMAL;
        private InterruptionBehavior interruptionBehavior = InterruptionBehavior.CANCEL_SELF;
        private List<ActionObject> actions;
        private List<LogicObject> logic;
        private EndAction endAction = interrupted -> { };
        private Duration watchdog = Duration.ZERO;
        private String refreshKey;

        private Builder(String name) {
            this.name = Objects.requireNonNull(name, "name");
        }

        /**
         * @param actuators actuators this container needs exclusively
         * @return this
         */
        public Builder requires(String... actuators) {
            spreadRequirementSet();
            ordered().addAll(List.of(actuators));
            return this;
        }

        /**
         * @param actuators actuators this container needs exclusively
         * @return this
         */
        public Builder requires(java.util.Collection<String> actuators) {
            if (requirements == null && requirementSet == null && actuators instanceof Set<String> set && !set.isEmpty()) {
                // Kept as it is when it is already unmodifiable (Set.copyOf returns it): a motor
                // platform gives the same set to every refresh of a drive, ten a second per robot.
                requirementSet = Set.copyOf(set);
                return this;
            }
            spreadRequirementSet();
            ordered().addAll(actuators);
            return this;
        }

        /** Moves a set given whole into the ordered requirements, before more are added. */
        private void spreadRequirementSet() {
            if (requirementSet != null) {
                ordered().addAll(requirementSet);
                requirementSet = null;
            }
        }

        private java.util.LinkedHashSet<String> ordered() {
            if (requirements == null) {
                requirements = new java.util.LinkedHashSet<>();
            }
            return requirements;
        }

        /**
         * @param value the priority (default NORMAL)
         * @return this
         */
        public Builder priority(CommandPriority value) {
            priority = Objects.requireNonNull(value);
            return this;
        }

        /**
         * @param value the interruption behavior (default CANCEL_SELF)
         * @return this
         */
        public Builder interruptionBehavior(InterruptionBehavior value) {
            interruptionBehavior = Objects.requireNonNull(value);
            return this;
        }

        /**
         * @param action run once at start
         * @return this
         */
        public Builder action(ActionObject action) {
            Objects.requireNonNull(action);
            if (actions == null) {
                actions = new ArrayList<>(2);
            }
            actions.add(action);
            return this;
        }

        /**
         * @param condition evaluated each cycle until it holds
         * @return this
         */
        public Builder logic(LogicObject condition) {
            Objects.requireNonNull(condition);
            if (logic == null) {
                logic = new ArrayList<>(2);
            }
            logic.add(condition);
            return this;
        }

        /**
         * @param action run when the container ends, finished or interrupted
         * @return this
         */
        public Builder onEnd(EndAction action) {
            endAction = Objects.requireNonNull(action);
            return this;
        }

        /**
         * @param timeout end the container (and run its end action) this long after it started,
         *                unless it finished; a continuous command is "refreshed" by submitting a new
         *                container for the same actuators. {@link Duration#ZERO} is off.
         * @return this
         */
        public Builder watchdog(Duration timeout) {
            if (timeout.isNegative()) {
                throw new IllegalArgumentException("watchdog timeout must be >= 0, got " + timeout);
            }
            watchdog = timeout;
            return this;
        }

        /**
         * Marks a continuous container that a newer one with the same key, actuators and priority
         * refreshes in place (its actions run, its watchdog restarts) instead of interrupting it.
         *
         * @param key the refresh key
         * @return this
         */
        public Builder refreshes(String key) {
            refreshKey = Objects.requireNonNull(key);
            return this;
        }

        /**
         * @return the container
         * @throws IllegalArgumentException if it requires no actuator
         */
        public Container build() {
            if ((requirements == null || requirements.isEmpty()) && requirementSet == null) {
                throw new IllegalArgumentException("container '" + name + "' requires no actuator; every container must name the actuators it drives");
            }
            return new Container(this);
        }
    }
}
