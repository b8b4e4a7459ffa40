package io.robomw.api;

import java.io.Serializable;
import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.function.Consumer;

/**
 * A handle on a travelling agent, kept at its home (after Aglets' {@code AgletProxy}). Hosts tell
 * the home where the agent is and how it is doing; the handle follows the agent from host to host,
 * so it stays valid while the agent travels. Once the agent's trip has ended (its result is home,
 * or it was disposed of or retracted) messages to it fail with {@link AgentException}.
 */
public interface AgentRef {

    /** @return the agent's id, the same on every host it visits */
    UUID id();

    /** @return the address of the host the agent was last known to be at */
    String location();

    /** @return the agent's last known status */
    AgentStatus status();

    /**
     * @return completes with the result the agent sets ({@link AgentContext#setResult}) when its
     *         trip ends, or exceptionally with an {@link AgentException} if it was disposed of, or set
     *         no result and one of its stops failed (the message names the stop and the cause)
     */
    CompletableFuture<Serializable> result();

    /**
     * The visits of the agent's trip, as its last host told the home when the trip ended: each
     * stop's host and how it ended ({@link Itinerary.Outcome}: done, failed with the remote stack
     * trace in its detail, unreachable with the reason, interrupted). Empty until the trip has
     * ended, and for hosts that do not tell it.
     *
     * @return the visits, in the order they happened
     */
    default List<Itinerary.Visit> history() {
        return List.of();
    }

    /**
     * Listens to the values the agent sends home while it travels ({@link AgentContext#report}),
     * in the order it sent them. Called on the home's delivery thread. The first listener added
     * also gets, first, the reports that came before it (an agent may report before the call that
     * sent it has returned), up to the last 10,000.
     *
     * @param listener the listener
     */
    void addReportListener(Consumer<Serializable> listener);

    /**
     * Like {@link #addReportListener(Consumer)}, and also tells where each value was sent from:
     * the address of the host the agent was at when it sent it (for a clone, the host it had
     * travelled to, not the one it was first sent to).
     *
     * @param listener called with the host's address and the value
     */
    default void onReport(java.util.function.BiConsumer<String, Serializable> listener) {
        addReportListener(v -> listener.accept(location(), v));
    }

    /**
     * Brings the agent home (after Aglets' {@code retractAglet}): the callback it is in is
     * interrupted (its thread's interrupt: a blocking verb ends its command and throws, a wait
     * ends; {@link AgentContext#leaving()} tells an agent that polls), its host stops the robot's
     * command if it drives, and once the callback returns it stops travelling and its state comes
     * home. Returns at once.
     *
     * @return completes with the agent as it was when it stopped
     */
    CompletableFuture<Agent> retract();

    /**
     * Asks nothing: completes with the agent as it was when it stopped, once it has come home
     * retracted, whoever asked for it ({@link #retract()} of this handle, {@code mw retract}, another
     * program); fails when its trip ends otherwise.
     *
     * @return the retracted agent's state, when it comes
     */
    default CompletableFuture<Agent> whenRetracted() {
        return CompletableFuture.failedFuture(new AgentException("this handle of agent " + id() + " does not follow retractions"));
    }

    /**
     * Disposes of the agent wherever it is: as {@link #retract()}, the callback it is in is
     * interrupted and the robot's command stopped; its trip ends there once the callback returns.
     * Returns at once.
     */
    void dispose();

    /**
     * Sends a message and blocks until the agent has handled it (Aglets' synchronous {@code sendMessage}).
     *
     * @param content the message
     * @param timeout how long to wait for the answer
     * @return the agent's reply, or {@code null} if it handled the message without replying
     * @throws NotHandledException if the agent did not handle it
     * @throws AgentException      if the agent cannot be reached, has ended its trip, or did not answer in time
     */
    Serializable sendMessage(Serializable content, Duration timeout);

    /**
     * Sends a message without waiting (Aglets' {@code sendFutureMessage}).
     *
     * @param content the message
     * @return completes with the reply, or exceptionally as {@link #sendMessage} would throw
     */
    CompletableFuture<Serializable> sendFutureMessage(Serializable content);

    /**
     * Sends a message and expects no answer (Aglets' {@code sendOnewayMessage}): no acknowledgement
     * is sent back, and a message the agent does not handle is dropped with a log line at its host.
     *
     * @param content the message
     */
    void sendOnewayMessage(Serializable content);
}
