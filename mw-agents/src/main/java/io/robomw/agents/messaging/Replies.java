package io.robomw.agents.messaging;

import io.robomw.api.Message;
import io.robomw.api.MessagingException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.Iterator;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.function.Predicate;

/**
 * Replies that arrived, and the threads waiting for them. A reply goes to the first waiter that
 * wants it; if none does, it is kept (up to {@value #MAX_UNCLAIMED}, oldest dropped first) for a
 * later {@code waitForReply}. Thread-safe.
 */
final class Replies {

    private static final Logger LOG = LoggerFactory.getLogger(Replies.class);
    static final int MAX_UNCLAIMED = 10_000;

    /**
     * One reply.
     *
     * @param message the reply
     * @param host    the address its request was sent to
     * @param error   the receiver's refusal, or {@code null} for a normal reply
     */
    record Reply(Message message, String host, String error) {
    }

    private record Waiter(String host, Predicate<Reply> wants, CompletableFuture<Message> future) {
    }

    private final Deque<Reply> unclaimed = new ArrayDeque<>();
    private final List<Waiter> waiters = new ArrayList<>();

    void arrived(Reply reply) {
        Waiter taker = null;
        synchronized (this) {
            for (Iterator<Waiter> it = waiters.iterator(); it.hasNext(); ) {
                Waiter w = it.next();
                if (w.wants.test(reply)) {
                    it.remove();
                    taker = w;
                    break;
                }
            }
            if (taker == null) {
                unclaimed.addLast(reply);
                if (unclaimed.size() > MAX_UNCLAIMED) {
                    Reply old = unclaimed.removeFirst();
                    LOG.warn("forgot an unclaimed reply on topic '{}' from {}: more than {} replies were never waited for",
                            old.message().topic(), old.host(), MAX_UNCLAIMED);
                }
            }
        }
        if (taker != null) {
            complete(taker.future, reply);
        }
    }

    /**
     * @param host  the host the reply must come from (for failing the wait when its link closes)
     * @param wants which reply
     * @return completes with the reply (or fails with the receiver's refusal)
     */
    CompletableFuture<Message> await(String host, Predicate<Reply> wants) {
        CompletableFuture<Message> future = new CompletableFuture<>();
        Reply found = null;
        synchronized (this) {
            for (Iterator<Reply> it = unclaimed.iterator(); it.hasNext(); ) {
                Reply r = it.next();
                if (wants.test(r)) {
                    it.remove();
                    found = r;
                    break;
                }
            }
            if (found == null) {
                waiters.add(new Waiter(host, wants, future));
            }
        }
        if (found != null) {
            complete(future, found);
        }
        return future;
    }

    synchronized void cancel(CompletableFuture<Message> future) {
        waiters.removeIf(w -> w.future == future);
    }

    /** Fails every wait for a reply from {@code host}, whose link closed. */
    void linkClosed(String host, String why) {
        List<Waiter> failed = new ArrayList<>();
        synchronized (this) {
            for (Iterator<Waiter> it = waiters.iterator(); it.hasNext(); ) {
                Waiter w = it.next();
                if (host.equals(w.host)) {
                    it.remove();
                    failed.add(w);
                }
            }
        }
        failed.forEach(w -> w.future.completeExceptionally(new MessagingException("the link to " + host + " closed before the reply came: " + why)));
    }

    private static void complete(CompletableFuture<Message> future, Reply reply) {
        if (reply.error() == null) {
            future.complete(reply.message());
        } else {
            future.completeExceptionally(new MessagingException(reply.host() + " refused the message on topic '"
                    + reply.message().topic() + "': " + reply.error()));
        }
    }
}
