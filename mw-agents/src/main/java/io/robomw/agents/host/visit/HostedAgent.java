package io.robomw.agents.host.visit;

import io.robomw.agents.host.AgentInfo;
import io.robomw.agents.host.messaging.AgentMessaging;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.api.Agent;
import io.robomw.api.AgentStatus;

import java.io.Serializable;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;

/**
 * An agent while it is at this host: the object, where it came from, and the requests made of it
 * (retract, dispose) that take effect when its current callback returns.
 */
public final class HostedAgent {

    public final UUID id;
    public final Agent agent;
    public final String className;
    public final ClassLoader loader;
    final CodeArchive.Digest digest;
    public final String home;
    /** Completes with the next host's address once the agent has left (for messages that arrive meanwhile). */
    public final CompletableFuture<String> departure = new CompletableFuture<>();
    public volatile long hop;
    public volatile long eventSeq;
    public volatile AgentStatus status = AgentStatus.ACTIVE;
    public volatile boolean retractRequested;
    public volatile boolean disposeRequested;
    volatile Serializable result;
    /** Whether the store has its stop marked started already ({@code AgentStore.acceptedStarting}): the runner does not mark it again. */
    volatile boolean startStored;
    /** The length of its image when it last travelled, to size the frame it is written into next. */
    volatile int imageSize;
    /** The runner thread while one of its callbacks (onArrival, the stop's work) runs, else {@code null}; guarded by this object. */
    private Thread working;
    /** Whether it took the host's robot during the callback running now. */
    public volatile boolean drives;
    /** When an operator's retract or dispose was asked while a callback ran (ms since the epoch), 0 if not. */
    public volatile long leaveAskedAt;
    /** Its view of the host's messaging, once it asked for it; guarded by this object. */
    public AgentMessaging messaging;

    public HostedAgent(AgentImage image, Agent agent, ClassLoader loader) {
        this.id = image.id();
        this.agent = agent;
        this.className = agent.getClass().getName();
        this.loader = loader;
        this.digest = image.digest();
        this.home = image.home();
        this.hop = image.hop();
        this.eventSeq = image.eventSeq();
        this.imageSize = image.stateLength() + 64;
    }

    /**
     * Its callbacks run on the calling thread from now until {@link #rested()}, unless an operator's
     * retract or dispose came first (after it arrived, before its work began): then they do not run
     * at all. Under this object's lock, as {@link #interruptWork()}: a retract either finds the work
     * running and interrupts it, or is found here.
     *
     * @return whether its callbacks may run
     */
    synchronized boolean working() {
        if (retractRequested || disposeRequested) {
            return false;
        }
        working = Thread.currentThread();
        drives = false;
        return true;
    }

    /**
     * Its callbacks have returned: the runner thread is no longer its own, and an interrupt meant for
     * the agent (a retract or dispose that came as the callback returned) is cleared, so that it
     * cannot reach the hop that follows or the runner's next agent.
     */
    synchronized void rested() {
        working = null;
        drives = false;
        Thread.interrupted();
    }

    /**
     * Interrupts the callback running now (the cooperative interrupt of a retract or dispose).
     *
     * @return the thread interrupted, or {@code null} if no callback of the agent runs
     */
    public synchronized Thread interruptWork() {
        if (working != null) {
            working.interrupt();
        }
        return working;
    }

    String shortId() {
        return id.toString().substring(0, 8);
    }

    public AgentInfo info() {
        AgentInfo.Pending pending = status != AgentStatus.ACTIVE || leaveAskedAt == 0 ? AgentInfo.Pending.NONE
                : retractRequested ? AgentInfo.Pending.RETRACT : disposeRequested ? AgentInfo.Pending.DISPOSE : AgentInfo.Pending.NONE;
        return new AgentInfo(id, className, status, hop, home, pending);
    }
}
