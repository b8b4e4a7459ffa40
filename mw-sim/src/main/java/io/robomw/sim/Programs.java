package io.robomw.sim;

import io.robomw.api.RobotException;
import io.robomw.sim.lockstep.Lockstep;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * Programs running on their own threads (named {@code program-N}) against a simulation's robots,
 * registered with its {@link Lockstep}: in a fast run, time advances only while they all wait for
 * their robots; in a real-time run, registration lets them wait while the run is paused. Collects
 * what they throw. Made by {@link Simulation#startPrograms}.
 */
public final class Programs {

    private final Lockstep lockstep;
    private final List<Thread> threads = new ArrayList<>();
    private final List<Throwable> failures = new CopyOnWriteArrayList<>();

    Programs(Lockstep lockstep, Runnable... programs) {
        this.lockstep = lockstep;
        for (Runnable program : programs) {
            Thread t = new Thread(() -> {
                try {
                    program.run();
                } catch (Throwable e) {
                    failures.add(e);
                } finally {
                    lockstep.finished();
                }
            }, "program-" + (threads.size() + 1));
            t.setDaemon(true);
            lockstep.register(t);
            threads.add(t);
        }
        threads.forEach(Thread::start);
    }

    /** @return the names of the program threads still running */
    public List<String> running() {
        return threads.stream().filter(Thread::isAlive).map(Thread::getName).toList();
    }

    /**
     * Waits a little for the threads to end (they are daemons; one still blocked is left).
     *
     * @param millis how long to wait for each
     */
    void join(long millis) {
        for (Thread t : threads) {
            try {
                t.join(millis);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
    }

    /**
     * @throws RobotException whose cause is the first failure, with the others suppressed, if a program failed
     */
    public void rethrowFailures() {
        if (!failures.isEmpty()) {
            Throwable first = failures.get(0);
            RobotException e = new RobotException("a program failed: " + first, first);
            failures.stream().skip(1).forEach(e::addSuppressed);
            throw e;
        }
    }

    /**
     * @param simSeconds the run's length, for the message
     * @throws RobotException if a program failed, or is still running
     */
    public void requireFinished(double simSeconds) {
        rethrowFailures();
        List<String> running = running();
        if (!running.isEmpty()) {
            throw new RobotException("programs did not finish within " + simSeconds + " s of simulated time; still running: " + running);
        }
    }
}
