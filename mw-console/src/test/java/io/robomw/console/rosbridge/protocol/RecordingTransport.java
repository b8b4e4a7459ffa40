package io.robomw.console.rosbridge.protocol;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * A client's connection for tests: keeps every frame sent. It takes each frame at once, or, when
 * {@link #hold() held}, not until {@link #release()} (a client that does not read).
 */
final class RecordingTransport implements Transport {

    /** A frame the client got. */
    record Sent(String text, byte[] binary) {
    }

    private final BlockingQueue<Sent> frames = new LinkedBlockingQueue<>();
    private final List<Runnable> held = new ArrayList<>();
    private boolean holding;
    volatile int closedWith;

    synchronized void hold() {
        holding = true;
    }

    /** Takes the frames held, and every later one at once. */
    void release() {
        List<Runnable> done;
        synchronized (this) {
            holding = false;
            done = new ArrayList<>(held);
            held.clear();
        }
        done.forEach(Runnable::run);
    }

    /** Completes one held send; the next frame is then sent (and held). */
    void releaseOne() {
        Runnable r;
        synchronized (this) {
            r = held.isEmpty() ? null : held.remove(0);
        }
        if (r != null) {
            r.run();
        }
    }

    @Override
    public void sendText(String text, Runnable done) {
        frames.add(new Sent(text, null));
        complete(done);
    }

    @Override
    public void sendBinary(byte[] data, Runnable done) {
        frames.add(new Sent(null, data));
        complete(done);
    }

    private void complete(Runnable done) {
        synchronized (this) {
            if (holding) {
                held.add(done);
                return;
            }
        }
        done.run();
    }

    @Override
    public void close(int code, String reason) {
        closedWith = code;
    }

    /** @return the next frame's text, waiting up to five seconds; fails if none comes */
    String next() throws InterruptedException {
        Sent s = frames.poll(5, TimeUnit.SECONDS);
        if (s == null) {
            throw new AssertionError("no frame came within 5 s");
        }
        if (s.text() == null) {
            throw new AssertionError("a binary frame came where a text frame was expected");
        }
        return s.text();
    }

    /** @return the next frame, binary or text, waiting up to five seconds */
    Sent nextFrame() throws InterruptedException {
        Sent s = frames.poll(5, TimeUnit.SECONDS);
        if (s == null) {
            throw new AssertionError("no frame came within 5 s");
        }
        return s;
    }

    /** @return every frame sent and not yet taken, without waiting */
    List<Sent> drain() {
        List<Sent> out = new ArrayList<>();
        frames.drainTo(out);
        return out;
    }
}
