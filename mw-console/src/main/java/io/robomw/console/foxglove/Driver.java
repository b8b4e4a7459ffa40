package io.robomw.console.foxglove;

import io.robomw.api.spi.FailurePolicy;
import io.robomw.api.spi.OwnerThread;

import org.slf4j.LoggerFactory;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;

/**
 * Hands the Twists clients publish to their robots, on a thread of its own ({@code foxglove-drive},
 * an {@link OwnerThread}), so a connection never waits for a robot (one reached over a network may
 * take a while to answer). Per robot only the latest Twist waits: a newer one replaces an older
 * one not yet handed on, as a velocity command should. Each is handed on once ({@link Teleop#drive});
 * the robot keeps driving until the next and stops by itself when the client stops publishing (its
 * watchdog). When a client unadvertises its channel or disconnects, the robot it drove is handed a
 * zero Twist at once, instead of waiting for the watchdog; so is every robot still driven by a
 * client when the server closes.
 */
final class Driver implements OwnerThread.Duty, AutoCloseable {

    /** The longest the thread waits for work before it looks again. */
    private static final long IDLE_NANOS = TimeUnit.MILLISECONDS.toNanos(200);

    private record Pending(Twist twist, ClientSession from) {
    }

    private final Teleop teleop;
    private final Map<String, Pending> pending = new LinkedHashMap<>();
    /** Who published last to each robot, and whether that asked it to move. */
    private final Map<String, Pending> last = new LinkedHashMap<>();
    private final OwnerThread thread;

    Driver(Teleop teleop, FailurePolicy failures) {
        this.teleop = teleop;
        this.thread = OwnerThread.start("foxglove-drive", Thread.NORM_PRIORITY, this, work -> {
            if (work == 0) {
                LockSupport.parkNanos(this, IDLE_NANOS);
            }
        }, failures);
    }

    /** Queues a Twist for a robot, replacing one still waiting. */
    void submit(String robot, Twist twist, ClientSession from) {
        synchronized (this) {
            pending.put(robot, new Pending(twist, from));
        }
        thread.wake();
    }

    /** The client no longer publishes to the robot: if it was the last to, and asked it to move, stop it now. */
    void release(String robot, ClientSession from) {
        synchronized (this) {
            Pending p = pending.containsKey(robot) ? pending.get(robot) : last.get(robot);
            if (p == null || p.from() != from || p.twist().equals(Twist.STOP)) {
                return;
            }
            pending.put(robot, new Pending(Twist.STOP, from));
        }
        thread.wake();
    }

    @Override
    public int doWork() {
        Map<String, Pending> batch;
        synchronized (this) {
            if (pending.isEmpty()) {
                return 0;
            }
            batch = new LinkedHashMap<>(pending);
            pending.clear();
            last.putAll(batch);
        }
        for (Map.Entry<String, Pending> e : batch.entrySet()) {
            Twist t = e.getValue().twist();
            try {
                teleop.drive(e.getKey(), t.linear(), t.angular());
            } catch (Exception ex) {
                e.getValue().from().driveFailed(e.getKey(), String.valueOf(ex.getMessage()));
            }
        }
        return batch.size();
    }

    @Override
    public void onClose() {
        List<String> moving = new ArrayList<>();
        synchronized (this) {
            last.putAll(pending);
            pending.clear();
            last.forEach((robot, p) -> {
                if (!p.twist().equals(Twist.STOP)) {
                    moving.add(robot);
                }
            });
        }
        for (String robot : moving) {
            try {
                teleop.drive(robot, 0, 0);
            } catch (Exception e) {
                LoggerFactory.getLogger(Driver.class).warn("foxglove: stopping robot {} as the server closes failed ({}); its watchdog stops it", robot, e.toString());
            }
        }
    }

    @Override
    public void close() {
        thread.close();
    }
}
