package io.robomw.sim.render;

import io.robomw.sim.Simulation;

import java.util.Locale;

/**
 * Pause, resume and speed of a simulation's real-time run, as a viewer's buttons and keys drive
 * them: the first resume starts the simulation's real-time thread; pausing and a new speed keep
 * it ({@link Simulation#pauseRealTime()}, {@link Simulation#setRealTimeSpeed}), so robot calls made
 * from other threads while paused wait instead of being refused; {@link #stop()} ends the run.
 * Speeds are powers of two from {@link #MIN_SPEED} to {@link #MAX_SPEED} simulated seconds per
 * wall-clock second.
 *
 * <p>Thread-safe. Only {@link #stop()} blocks, for at most one step.
 */
public final class RealTimeControl {

    /** Slowest speed: a sixteenth of real time. */
    public static final double MIN_SPEED = 1.0 / 16;
    /** Fastest speed: 64 times real time (the world may not keep up; then it runs as fast as it can). */
    public static final double MAX_SPEED = 64;

    private final Simulation simulation;
    private double speed;
    private boolean started;
    private boolean running;
    private boolean stopped;

    /**
     * Makes a control; the run is paused until {@link #resume()}.
     *
     * @param simulation the simulation, not running in real time or with programs
     * @param speed      the first speed, between {@link #MIN_SPEED} and {@link #MAX_SPEED}
     */
    public RealTimeControl(Simulation simulation, double speed) {
        this.simulation = simulation;
        this.speed = checked(speed);
    }

    private static double checked(double speed) {
        if (!(speed >= MIN_SPEED && speed <= MAX_SPEED)) {
            throw new IllegalArgumentException("speed must be between " + MIN_SPEED + " and " + MAX_SPEED + " × real time, got " + speed);
        }
        return speed;
    }

    /** Starts (or continues) the real-time run at the current speed; returns at once. Nothing happens after {@link #stop()}. */
    public synchronized void resume() {
        if (running || stopped) {
            return;
        }
        if (started) {
            simulation.resumeRealTime();
        } else {
            simulation.startRealTime(speed);
            started = true;
        }
        running = true;
    }

    /** Pauses the real-time run: simulated time stands still until {@link #resume()}. */
    public synchronized void pause() {
        if (running) {
            simulation.pauseRealTime();
            running = false;
        }
    }

    /** Pauses a running simulation, resumes a paused one; may block for one step. */
    public synchronized void togglePause() {
        if (running) {
            pause();
        } else {
            resume();
        }
    }

    /**
     * Doubles the speed, up to {@link #MAX_SPEED}; may block for one step.
     *
     * @return the new speed
     */
    public synchronized double faster() {
        return setSpeed(Math.min(MAX_SPEED, speed * 2));
    }

    /**
     * Halves the speed, down to {@link #MIN_SPEED}; may block for one step.
     *
     * @return the new speed
     */
    public synchronized double slower() {
        return setSpeed(Math.max(MIN_SPEED, speed / 2));
    }

    /**
     * Sets the speed; a running simulation is stopped and started again at it, which blocks for
     * one step.
     *
     * @param newSpeed simulated seconds per wall-clock second
     * @return the new speed
     */
    public synchronized double setSpeed(double newSpeed) {
        checked(newSpeed);
        if (newSpeed != speed) {
            speed = newSpeed;
            if (started) {
                simulation.setRealTimeSpeed(speed);
            }
        }
        return speed;
    }

    /** Stops the run for good (the viewer closed); blocks for one step. Later calls to {@link #resume()} do nothing. */
    public synchronized void stop() {
        running = false;
        stopped = true;
        simulation.stopRealTime();
    }

    /** @return simulated seconds per wall-clock second */
    public synchronized double speed() {
        return speed;
    }

    /** @return whether the world is being stepped in real time now */
    public synchronized boolean isRunning() {
        return running;
    }

    /**
     * @param speed a speed
     * @return it for people: {@code 1/4×}, {@code 1×}, {@code 16×}
     */
    public static String format(double speed) {
        return speed >= 1 ? String.format(Locale.ROOT, "%.0f×", speed) : String.format(Locale.ROOT, "1/%.0f×", 1 / speed);
    }
}
