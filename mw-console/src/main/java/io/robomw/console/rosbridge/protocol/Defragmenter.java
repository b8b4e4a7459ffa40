package io.robomw.console.rosbridge.protocol;

import java.util.HashMap;
import java.util.Iterator;
import java.util.Map;
import java.util.Optional;

/**
 * Puts together the messages one client sends in {@code fragment} frames
 * ({@code {op: fragment, id, data, num, total}}: the {@code data} of fragments 0 to total - 1, in
 * order, are the message's JSON text), as rosbridge_suite's {@code defragmentation} capability
 * does. Fragments may come in any order. Bounded: at most {@link Limits#maxPartialMessages}
 * messages at once, each at most {@link Limits#maxMessageBytes} characters, and a message not
 * complete within {@link Limits#fragmentTimeout} is forgotten. Used on one client's thread.
 */
final class Defragmenter {

    private final Limits limits;
    private final Map<String, Partial> partial = new HashMap<>();

    private static final class Partial {
        final String[] pieces;
        final long started;
        int received;
        long chars;

        Partial(int total, long started) {
            this.pieces = new String[total];
            this.started = started;
        }
    }

    Defragmenter(Limits limits) {
        this.limits = limits;
    }

    /**
     * @param id        the message's id
     * @param data      this fragment's text
     * @param num       its index, from 0
     * @param total     how many fragments the message has
     * @param nowNanos  the time now, {@link System#nanoTime()}
     * @return the whole message once its last fragment came
     * @throws IllegalArgumentException if the fragment does not fit its message or a limit
     */
    Optional<String> add(String id, String data, int num, int total, long nowNanos) {
        expire(nowNanos);
        if (total < 1 || num < 0 || num >= total) {
            throw new IllegalArgumentException("fragment " + num + " of " + total + " of message '" + id + "': num must be 0 to total - 1");
        }
        if (total > limits.maxMessageBytes()) {
            throw new IllegalArgumentException("message '" + id + "' in " + total + " fragments: more than " + limits.maxMessageBytes() + " is not taken");
        }
        Partial p = partial.get(id);
        if (p == null) {
            if (partial.size() >= limits.maxPartialMessages()) {
                throw new IllegalArgumentException("fragment of message '" + id + "': already " + partial.size()
                        + " messages partly received, the most a client may send at once");
            }
            p = new Partial(total, nowNanos);
            partial.put(id, p);
        } else if (p.pieces.length != total) {
            partial.remove(id);
            throw new IllegalArgumentException("fragment of message '" + id + "' says " + total + " fragments, earlier ones said " + p.pieces.length
                    + "; the message is dropped");
        }
        if (p.pieces[num] == null) {
            p.received++;
        } else {
            p.chars -= p.pieces[num].length();
        }
        p.pieces[num] = data;
        p.chars += data.length();
        if (p.chars > limits.maxMessageBytes()) {
            partial.remove(id);
            throw new IllegalArgumentException("message '" + id + "' in fragments is over " + limits.maxMessageBytes() + " characters; it is dropped");
        }
        if (p.received < total) {
            return Optional.empty();
        }
        partial.remove(id);
        return Optional.of(String.join("", p.pieces));
    }

    /** @return messages partly received */
    int pending() {
        return partial.size();
    }

    private void expire(long nowNanos) {
        long timeout = limits.fragmentTimeout().toNanos();
        for (Iterator<Partial> it = partial.values().iterator(); it.hasNext(); ) {
            if (nowNanos - it.next().started > timeout) {
                it.remove();
            }
        }
    }
}
