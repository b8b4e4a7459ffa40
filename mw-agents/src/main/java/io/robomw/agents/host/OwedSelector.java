package io.robomw.agents.host;

import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.net.WireCode;
import io.robomw.agents.net.WireCodes;

import java.util.Objects;
import java.util.UUID;

/**
 * Which owed deliveries to drop ({@link AgentHost#dropOwed}, {@code mw agents --drop-owed}): all of
 * them, those of one agent, or those owed to one home. It travels in a DROP_OWED call as its
 * {@link Kind#code()} and argument ({@link Bodies}).
 *
 * @param kind  what it selects by
 * @param agent the agent, for {@link Kind#AGENT}
 * @param home  the home's address, for {@link Kind#HOME}
 */
public record OwedSelector(Kind kind, UUID agent, String home) {

    /** What a selector selects by. Each travels as its {@link #code()}. */
    public enum Kind implements WireCode {
        /** Every owed delivery. */
        ALL(0),
        /** The deliveries of one agent. */
        AGENT(1),
        /** The deliveries owed to one home. */
        HOME(2);

        private static final WireCodes<Kind> CODES = WireCodes.of(Kind.class, "owed-delivery selector");

        private final int code;

        Kind(int code) {
            this.code = code;
        }

        /** @return the kind's code in a DROP_OWED body */
        @Override
        public int code() {
            return code;
        }

        /**
         * @param code a kind byte as read (unsigned)
         * @return its kind
         * @throws IllegalArgumentException naming the code if no kind has it
         */
        public static Kind fromCode(int code) {
            return CODES.get(code);
        }
    }

    /** Checks that the argument the kind needs is there. */
    public OwedSelector {
        Objects.requireNonNull(kind, "kind");
        if (kind == Kind.AGENT && agent == null || kind == Kind.HOME && (home == null || home.isBlank())) {
            throw new IllegalArgumentException("an owed-delivery selector by " + kind + " needs " + (kind == Kind.AGENT ? "an agent id" : "a home address"));
        }
    }

    /** @return a selector of every owed delivery */
    public static OwedSelector all() {
        return new OwedSelector(Kind.ALL, null, null);
    }

    /** @param agent an agent @return a selector of its owed deliveries */
    public static OwedSelector agent(UUID agent) {
        return new OwedSelector(Kind.AGENT, agent, null);
    }

    /** @param home a home's address @return a selector of the deliveries owed to it */
    public static OwedSelector home(String home) {
        return new OwedSelector(Kind.HOME, null, home);
    }

    /** @param d an owed delivery @return whether this selects it */
    public boolean matches(OwedDelivery d) {
        return switch (kind) {
            case ALL -> true;
            case AGENT -> d.agent().equals(agent);
            case HOME -> d.home().equals(home);
        };
    }

    @Override
    public String toString() {
        return switch (kind) {
            case ALL -> "all";
            case AGENT -> "agent " + agent;
            case HOME -> "home " + home;
        };
    }
}
