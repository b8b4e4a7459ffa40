package io.robomw.console.server;

import java.util.UUID;

/**
 * What the page's buttons do. The console holds the cluster key and the robots' links; the page
 * never sees either. Each method returns a line for the page, or throws with one.
 */
public interface Controls {

    /** @return whether agents can be retracted and disposed of (the console has a cluster key) */
    boolean agentsControllable();

    /** @return why not, when they cannot ("" when they can) */
    default String agentsWhyNot() {
        return agentsControllable() ? "" : "this console was started without a cluster key (--key-file or MW_CLUSTER_KEY), so it cannot retract or dispose of agents";
    }

    /** @param agent an agent @return what happened @throws Exception with a line for the page */
    String retract(UUID agent) throws Exception;

    /** @param agent an agent @return what happened @throws Exception with a line for the page */
    String dispose(UUID agent) throws Exception;

    /** @param robot a robot the console watches @return what happened @throws Exception with a line for the page */
    String stop(String robot) throws Exception;

    /** @return the robots {@link #stop} can stop (a robot driven through its brick by another process cannot be) */
    default java.util.Set<String> stoppableRobots() {
        return java.util.Set.of();
    }

    /** No buttons: a replay, or a console without key or robots. */
    Controls NONE = new Controls() {
        @Override
        public boolean agentsControllable() {
            return false;
        }

        @Override
        public String agentsWhyNot() {
            return "this console only watches (a replay, or no cluster key)";
        }

        @Override
        public String retract(UUID agent) {
            throw new IllegalStateException(agentsWhyNot());
        }

        @Override
        public String dispose(UUID agent) {
            throw new IllegalStateException(agentsWhyNot());
        }

        @Override
        public String stop(String robot) {
            throw new IllegalStateException("this console cannot stop robots (a replay)");
        }
    };
}
