package io.robomw.agents.messaging.tcp;

import java.util.ArrayDeque;
import java.util.concurrent.locks.LockSupport;

/**
 * Who reads one connection now (leader/follower): its reader thread, or a thread waiting for a
 * reply on it. At most one thread leads at a time; leadership changes hands under one lock, so
 * each leader sees everything its predecessor read (the connection's frame buffer and counters).
 *
 * <p>A waiting thread leads when nobody does; one that finds a leader <em>follows</em> (asks to
 * lead next). Whoever releases wakes the first follower; with none, the reader thread takes
 * leadership back: woken at once if bytes are known to wait, else when it next looks (it looks
 * every millisecond while it does not lead; {@code TcpConnection.READER_LOOKS_NANOS}), so that a
 * thread that sends and waits over and over finds leadership free rather than the reader thread
 * blocked in a read. The reader thread takes leadership only when no follower asks for it, and
 * gives it up (between frames, when it would have to block) as soon as one does.
 * {@link #releaseToReader} hands it to the reader thread whatever follows: a waiting thread never
 * runs listeners, so it leaves a frame for one, and all that comes after it, to the reader thread.
 *
 * <p>Thread-safe.
 */
final class ReadLeadership {

    private final ArrayDeque<Thread> followers = new ArrayDeque<>();
    private Thread reader;
    private Thread leader;
    /** The reader thread must lead next (a frame for a listener waits for it). */
    private boolean readerNext;
    private boolean closed;
    /** How many threads follow: read by the leading reader thread between frames, without the lock. */
    private volatile int following;

    /** @param t the connection's reader thread (set once, before it starts) */
    synchronized void reader(Thread t) {
        reader = t;
    }

    /**
     * @param t the calling thread
     * @return whether {@code t} leads now (it already did, or took the free leadership)
     */
    synchronized boolean tryLead(Thread t) {
        if (leader == t) {
            return true;
        }
        if (leader != null || closed) {
            return false;
        }
        if (t == reader) {
            if (!followers.isEmpty() && !readerNext) {
                return false;
            }
            readerNext = false;
        } else if (readerNext) {
            return false;
        }
        leader = t;
        if (followers.remove(t)) {
            following = followers.size();
        }
        return true;
    }

    /** @return whether {@code t} leads */
    synchronized boolean leads(Thread t) {
        return leader == t;
    }

    /** @return whether a waiting thread asks to lead (a hint, read without the lock) */
    boolean followersWaiting() {
        return following > 0;
    }

    /** @param t a waiting thread that asks to lead next; it is woken ({@code unpark}) when it may */
    synchronized void follow(Thread t) {
        if (!followers.contains(t)) {
            followers.addLast(t);
            following = followers.size();
        }
    }

    /**
     * A waiting thread no longer asks to lead (it got its reply, or stopped waiting). If it may
     * have been woken to lead and nobody leads, the next follower is woken instead (or the reader
     * thread, if it must lead next); with no follower left the reader thread takes over when it
     * next looks, as after {@link #release}: waking it now would mostly put it back in a read just
     * before this thread, which waited for replies, sends and waits again.
     *
     * @param t the thread
     */
    void unfollow(Thread t) {
        Thread next = null;
        synchronized (this) {
            if (followers.remove(t)) {
                following = followers.size();
            }
            if (leader == null && !closed) {
                next = readerNext ? reader : followers.peekFirst();
            }
        }
        LockSupport.unpark(next);
    }

    /**
     * The leader stops leading: the first follower is woken to lead; if none, the reader thread is
     * woken if frames wait, else it takes over when it next looks, so that a thread that waits for replies
     * one after the other finds leadership free again instead of the reader thread blocked in a read.
     *
     * @param framesWait whether bytes of the stream are known to wait (buffered or in the socket)
     */
    void release(boolean framesWait) {
        Thread next;
        synchronized (this) {
            leader = null;
            next = readerNext ? reader : followers.peekFirst();
            if (next == null && framesWait) {
                next = reader;
            }
        }
        LockSupport.unpark(next);
    }

    /** The leader stops leading, and the reader thread must lead next (a frame for a listener waits for it). */
    void releaseToReader() {
        Thread next;
        synchronized (this) {
            leader = null;
            readerNext = true;
            next = reader;
        }
        LockSupport.unpark(next);
    }

    /** The connection closed: nobody leads any more; the reader thread is woken to end. */
    void close() {
        Thread r;
        synchronized (this) {
            closed = true;
            r = reader;
        }
        LockSupport.unpark(r);
    }

}
