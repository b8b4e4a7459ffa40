package io.robomw.agents.messaging.robot;

import io.robomw.api.CommandPreemptedException;
import io.robomw.api.MessagingException;
import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;
import io.robomw.api.UnsupportedActionException;

import java.util.List;
import java.util.Set;

/**
 * The exceptions that travel from a served robot back to its remote callers, so that a remote
 * {@code move} throws what a local one would. An exception of another class, or with a cause that
 * is not one of these, is replaced by one that is (a {@link RobotLinkException} keeps its class
 * and carries the cause's text).
 */
final class RobotFailures {

    /** The exception classes that travel as themselves. */
    static final List<Class<? extends Throwable>> TRAVELLING = List.of(
            UnsupportedActionException.class, CommandPreemptedException.class, RobotLinkException.class, MessagingException.class,
            RobotException.class, IllegalArgumentException.class, IllegalStateException.class, NullPointerException.class,
            UnsupportedOperationException.class, ArithmeticException.class);

    /** What else serializing one of them involves. */
    static final Set<String> INTERNALS = Set.of("java.lang.Throwable", "java.lang.Exception", "java.lang.RuntimeException",
            "java.lang.StackTraceElement", "java.util.Collections$EmptyList", "java.util.Collections$UnmodifiableRandomAccessList",
            "java.util.Collections$UnmodifiableList", "java.util.Collections$UnmodifiableCollection", "java.util.ArrayList");

    private RobotFailures() {
    }

    /**
     * @param t what the served robot threw
     * @return an exception that can travel: {@code t} itself, or a stand-in
     */
    static Throwable travelling(Throwable t) {
        if (t instanceof java.util.concurrent.CompletionException && t.getCause() != null) {
            t = t.getCause();
        }
        if (travels(t)) {
            return t;
        }
        Throwable standIn;
        if (t instanceof RobotLinkException) {
            standIn = new RobotLinkException(t.getMessage() + (t.getCause() == null ? "" : " (cause: " + t.getCause() + ")"), null);
        } else {
            standIn = new RobotException("the served robot failed: " + t);
        }
        standIn.setStackTrace(t.getStackTrace());
        return standIn;
    }

    private static boolean travels(Throwable t) {
        for (Throwable c = t; c != null; c = c.getCause() == c ? null : c.getCause()) {
            if (!TRAVELLING.contains(c.getClass()) || c.getSuppressed().length > 0) {
                return false;
            }
        }
        return true;
    }
}
