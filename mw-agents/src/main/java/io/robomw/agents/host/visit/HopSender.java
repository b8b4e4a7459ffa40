package io.robomw.agents.host.visit;

import io.robomw.agents.host.core.HostState;
import io.robomw.agents.host.home.AgentHandle;
import io.robomw.agents.host.protocol.AgentImage;
import io.robomw.agents.host.protocol.Bodies;
import io.robomw.agents.host.protocol.Frame;
import io.robomw.agents.host.protocol.Op;
import io.robomw.agents.host.protocol.Reply;
import io.robomw.agents.host.rmi.PeerException;
import io.robomw.agents.host.rmi.Peers;
import io.robomw.agents.host.code.CodeArchive;
import io.robomw.agents.host.code.StateCodec;
import io.robomw.api.AgentStatus;
import io.robomw.api.Itinerary;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;

/**
 * Carries one agent to one host: records it departing, makes the transfer (sending the code
 * archive first when the host asks for it) with the itinerary's retries, and once the host has
 * acknowledged, records it departed and remembers where it went.
 *
 * <p>A transfer that may have reached the host (the connection broke mid-call) is asked of that
 * same host again until it answers, never sent elsewhere: only that host may have the agent, and
 * hops are numbered, so it takes the agent at most once.
 */
public final class HopSender {

    private static final Logger LOG = LoggerFactory.getLogger(HopSender.class);
    private static final long MAX_RESEND_BACKOFF_MILLIS = 5_000;

    private final HostState host;
    private final Peers peers;

    public HopSender(HostState host, Peers peers) {
        this.host = host;
        this.peers = peers;
    }

    /**
     * @param target a host
     * @return the form of agent state it reads: compact if this host's session with it is of agent
     *         protocol version 5 or later; standard, which every build reads, for a host of a build
     *         before it, and while this host has no session with it yet (its first agent there)
     */
    StateCodec.Form stateFormOf(String target) {
        return peers.stateFormOf(target);
    }

    /**
     * Delivers an image to a host, with the itinerary's retries.
     *
     * @param h      the agent
     * @param image  its image (the header of {@code raw})
     * @param raw    the image in the transfer call's frame
     * @param target the host
     * @param it     the itinerary whose policy, retries and back-off apply
     * @return {@code null} once delivered; why not, if the stop is unreachable
     */
    String send(HostedAgent h, AgentImage image, Frame raw, String target, Itinerary it) {
        try {
            host.store.departing(h.id, image.hop(), raw.bytes, raw.bodyOffset(), raw.bodyLength());
        } catch (IOException e) {
            LOG.warn("host {}: cannot record agent {} departing: {}", host.name, h.id, e.toString());
        }
        h.status = AgentStatus.IN_TRANSIT;
        int attempts = it.unreachablePolicy() == Itinerary.UnreachablePolicy.RETRY ? 1 + it.retries() : 1;
        String why = null;
        for (int a = 0; a < attempts && !host.closed; a++) {
            if (a > 0 && !pause(it.retryBackoff().toMillis())) {
                break;
            }
            if (a > 0 && (h.retractRequested || h.disposeRequested)) {
                why = (h.retractRequested ? "retracted" : "disposed of") + " while it waited to reach " + target + " (" + why + ")";
                break;
            }
            try {
                transfer(image, raw, target);
                arrivedElsewhere(h, image, target);
                return null;
            } catch (RefusedException e) {
                why = e.getMessage();
                break;
            } catch (PeerException e) {
                why = e.getMessage();
                if (!e.delivered() && a + 1 < attempts) {
                    LOG.warn("host {}: agent {} cannot reach its next stop {} (attempt {} of {}): {}; trying again in {} ms", host.name, h.id, target, a + 1,
                            attempts, why, it.retryBackoff().toMillis());
                }
                if (e.delivered()) {
                    // It may be there already: only that host may have it, so ask it until it answers.
                    if (resendUntilAnswered(image, raw, target)) {
                        arrivedElsewhere(h, image, target);
                        return null;
                    }
                    return "host closed while the transfer was unanswered";
                }
            }
        }
        h.status = AgentStatus.ACTIVE;
        return why == null ? "the host is closing" : why;
    }

    private void arrivedElsewhere(HostedAgent h, AgentImage image, String target) {
        h.hop = image.hop();
        try {
            // Only the copy that left with this hop: on a hop to this same host the new copy is stored already.
            host.store.departed(h.id, image.hop());
        } catch (IOException e) {
            LOG.warn("host {}: cannot record agent {} departed: {}", host.name, h.id, e.toString());
        }
        host.forwarded(h.id, target);
        // The next host has it: it is no longer here (only this object: the agent may be back already).
        host.hosted.remove(h.id, h);
        h.departure.complete(target);
        AgentHandle handle = host.handles.get(h.id);
        if (handle != null) {
            // This host is the agent's home and the target has acknowledged: it is there now.
            handle.arrived(target);
        }
    }

    private boolean resendUntilAnswered(AgentImage image, Frame raw, String target) {
        long backoff = 200;
        while (!host.closed) {
            if (!pause(backoff)) {
                return false;
            }
            try {
                transfer(image, raw, target);
                return true;
            } catch (RefusedException e) {
                LOG.error("host {}: {} refused agent {} after a transfer that may have reached it: {}; keeping it here", host.name, target, image.id(),
                        e.getMessage());
                return false;
            } catch (PeerException e) {
                LOG.warn("host {}: transfer of agent {} to {} still unanswered ({}); asking again in {} ms", host.name, image.id(), target, e.getMessage(),
                        backoff);
                backoff = Math.min(MAX_RESEND_BACKOFF_MILLIS, backoff * 2);
            }
        }
        return false;
    }

    private static boolean pause(long millis) {
        try {
            Thread.sleep(millis); // the itinerary's retry back-off, not a wait for a condition
            return true;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return false;
        }
    }

    /** A host refused an agent or archive outright: it did not take it, and will not. */
    private static final class RefusedException extends Exception {
        private static final long serialVersionUID = 1L;

        RefusedException(String message) {
            super(message);
        }
    }

    private void transfer(AgentImage image, Frame raw, String target) throws PeerException, RefusedException {
        Reply r = peers.call(target, Op.TRANSFER, raw);
        if (r.status() == Reply.Status.NEED_ARCHIVE) {
            CodeArchive archive = host.store.archive(image.digest())
                    .orElseThrow(() -> new RefusedException("this host lacks archive " + image.digest() + " that " + target + " asks for"));
            Reply a = peers.call(target, Op.PUT_ARCHIVE, Bodies.archive(archive));
            if (a.status() != Reply.Status.OK) {
                throw new RefusedException(target + " refused archive " + archive.digest() + ": " + a.text());
            }
            r = peers.call(target, Op.TRANSFER, raw);
        }
        switch (r.status()) {
            case OK, DUPLICATE -> {
            }
            case REFUSED -> throw new RefusedException(target + " refused agent " + image.id() + ": " + r.text());
            default -> throw new RefusedException(target + " answered " + r.status() + " to a transfer");
        }
    }
}
