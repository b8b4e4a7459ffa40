package io.robomw.cli;

import io.robomw.api.AgentRef;
import io.robomw.api.Itinerary;

import java.io.PrintWriter;
import java.time.Duration;
import java.util.List;
import java.util.Map;

/**
 * The end of {@code mw dispatch}: every stop of every agent sent, and every host whose clone was
 * not sent. A stop is DONE, FAILED (with the remote stack trace; for a user error such as a host
 * without a robot, one line unless {@code --verbose}), UNREACHABLE (with the reason) or
 * INTERRUPTED (its host stopped while it ran). An agent whose result did not come home in time is
 * listed with its status and where it was last seen.
 */
final class TripSummary {

    /**
     * An agent that was sent.
     *
     * @param label how its lines are labelled: its first host (clones) or its short id
     * @param ref   its handle
     */
    record Sent(String label, AgentRef ref) {
    }

    private final List<Sent> sent;
    private final Map<String, String> unsent;
    private final boolean verbose;

    TripSummary(List<Sent> sent, Map<String, String> unsent, boolean verbose) {
        this.sent = sent;
        this.unsent = unsent;
        this.verbose = verbose;
    }

    /** @return how many stops were skipped: unreachable, interrupted, or a clone not sent */
    int skippedStops() {
        int n = unsent.size();
        for (Sent s : sent) {
            n += (int) s.ref().history().stream()
                    .filter(v -> v.outcome() == Itinerary.Outcome.UNREACHABLE || v.outcome() == Itinerary.Outcome.INTERRUPTED).count();
        }
        return n;
    }

    /**
     * @param out     where to write
     * @param timeout the time-out that passed, or {@code null} when every result came home
     */
    void print(PrintWriter out, Duration timeout) {
        out.println("summary:");
        for (Sent s : sent) {
            AgentRef ref = s.ref();
            boolean home = ref.result().isDone();
            Verdict verdict = verdict(ref);
            if (home) {
                out.printf("  %-10s [%s] agent %s %s %s%s%n", verdict, s.label(), ref.id(), verdict == Verdict.RETRACTED ? "came home from" : "ended at",
                        ref.location(), skipped(ref));
            } else {
                out.printf("  %-10s [%s] agent %s: no result within %s; last seen %s at %s%n", verdict, s.label(), ref.id(), timeout, ref.status(),
                        ref.location());
            }
            for (Itinerary.Visit v : ref.history()) {
                printVisit(out, v);
            }
            if (home && ref.history().isEmpty()) {
                out.println("    (its last host did not say how its stops went)");
            }
        }
        unsent.forEach((host, why) -> out.printf("  %-10s [%s]%n    %-11s  %s: %s%n", "NOT-SENT", host, "UNREACHABLE", host, flat(why)));
    }

    /** What happened to an agent, the first word of its summary line. */
    enum Verdict {
        /** Its result came home and every stop was done. */
        COMPLETED,
        /** Its result came home, but a stop was unreachable or interrupted (its host stopped or crashed). */
        INCOMPLETE,
        /** Its trip failed, or a stop failed. */
        FAILED,
        /** It was retracted: its state came home. */
        RETRACTED,
        /** It was disposed of. */
        DISPOSED,
        /** No result within the time-out: it may still be travelling. */
        OUT
    }

    static Verdict verdict(AgentRef ref) {
        if (!ref.result().isDone()) {
            return Verdict.OUT;
        }
        if (ref.status() == io.robomw.api.AgentStatus.RETRACTED) {
            return Verdict.RETRACTED;
        }
        if (ref.status() == io.robomw.api.AgentStatus.DISPOSED) {
            return Verdict.DISPOSED;
        }
        if (ref.result().isCompletedExceptionally() || ref.history().stream().anyMatch(v -> v.outcome() == Itinerary.Outcome.FAILED)) {
            return Verdict.FAILED;
        }
        return ref.history().stream().allMatch(v -> v.outcome() == Itinerary.Outcome.DONE) ? Verdict.COMPLETED : Verdict.INCOMPLETE;
    }

    /** @return ", 1 stop interrupted, 2 unreachable", or nothing when no stop was skipped */
    private static String skipped(AgentRef ref) {
        long interrupted = ref.history().stream().filter(v -> v.outcome() == Itinerary.Outcome.INTERRUPTED).count();
        long unreachable = ref.history().stream().filter(v -> v.outcome() == Itinerary.Outcome.UNREACHABLE).count();
        StringBuilder b = new StringBuilder();
        if (interrupted > 0) {
            b.append(", ").append(interrupted).append(interrupted == 1 ? " stop" : " stops").append(" interrupted");
        }
        if (unreachable > 0) {
            b.append(", ").append(unreachable).append(interrupted > 0 ? "" : unreachable == 1 ? " stop" : " stops").append(" unreachable");
        }
        return b.toString();
    }

    private void printVisit(PrintWriter out, Itinerary.Visit v) {
        String detail = v.detail() == null ? "" : v.detail();
        switch (v.outcome()) {
            case DONE -> out.printf("    %-11s  %s%n", "DONE", v.host());
            case FAILED -> {
                String first = firstLine(detail);
                out.printf("    %-11s  %s: %s%n", "FAILED", v.host(), first);
                String trace = detail.substring(first.length()).strip();
                if (!trace.isEmpty() && (verbose || !userError(first))) {
                    trace.lines().forEach(l -> out.println("                 " + l.strip()));
                }
            }
            default -> out.printf("    %-11s  %s: %s%n", v.outcome(), v.host(), flat(detail));
        }
    }

    /** A failure that is the user's to fix (a host without a robot, an action the robot cannot do): its trace helps nobody. */
    private static boolean userError(String firstLine) {
        return firstLine.startsWith("io.robomw.agents.host.NoRobotException") || firstLine.startsWith("io.robomw.api.UnsupportedActionException");
    }

    /** @return a reason on one line (RMI's messages nest their causes on new lines) */
    static String flat(String text) {
        return text == null ? "" : text.strip().replaceAll("\\s*\\R\\s*", " ");
    }

    private static String firstLine(String detail) {
        int nl = detail.indexOf('\n');
        return nl < 0 ? detail : detail.substring(0, nl);
    }
}
