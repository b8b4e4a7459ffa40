package io.robomw.platform.motor;

import io.robomw.api.Clock;

import java.io.IOException;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.concurrent.locks.LockSupport;

/**
 * The link side of a {@link MotorPlatform}: what the brick's link agent runs once a round. It
 * takes the states the action side published, adds the stops the link side decides itself, hands
 * the batch to the {@link MotorDriver}, then polls it; the driver's readings come back through
 * {@link #feedback()}. A rotation counts from a reading: the first round after the link was opened
 * or reopened reads the brick before it sends anything.
 *
 * <h2>Stops the link side decides</h2>
 * <ul>
 *   <li><b>At the brick's own limit.</b> A brick that ends a limited rotation itself (the NXT's
 *   tacho limit) says so through {@link FeedbackSink#stoppedAtLimit}: the rotation is over for the
 *   action side, and one meant to end braked is braked with the next batch, from here. The brake
 *   the action side then publishes for it equals what was sent and is not sent again: the end of a
 *   move crosses from the link side to the action side once, not back.</li>
 *   <li><b>Just in time.</b> On a slow link ({@link LinkTiming#stopsOnLinkSide()}: the RCX's
 *   infra-red, an NXT without tacho limits) every limited rotation that reaches its target, by
 *   prediction, before the link side's next chance to send ({@link LinkTiming#nextSendNanos}) is
 *   stopped in this batch, at the mean of the moments each should be sent (a stop sent then
 *   reaches the brick as the motor reaches its target); two motors of one move or turn, started
 *   together at one speed, stop together. On a link agent's own thread the service waits for that
 *   moment; inline (a simulation's cycling thread) time is the owner's to step.</li>
 * </ul>
 *
 * <p>Link side only: one thread at a time (the link agent's, or the cycling thread inline).
 */
public final class MotorLinkSide {

    private final MotorPlatform motors;
    private final Clock clock;
    private final MotorPort[] ports;
    private final MotorDriver driver;
    private final LinkTiming timing;
    private final RotationPredictor predictor;
    private final MotorHandOff handOff;
    private final Feedback feedback = new Feedback();
    /** Whether a just-in-time stop may wait for its moment: the link side has a thread of its own. */
    private volatile boolean mayWait = true;
    /** Whether the driver has been polled since the link was opened or last reopened; link side. */
    private volatile boolean polled;

    MotorLinkSide(MotorPlatform motors, MotorPort[] ports, MotorDriver driver, RotationPredictor predictor, MotorHandOff handOff) {
        this.motors = motors;
        this.clock = motors.clock();
        this.ports = ports;
        this.driver = driver;
        this.timing = driver.timing();
        this.predictor = predictor;
        this.handOff = handOff;
    }

    /** Serviced inline on the cycling thread: a stop just in time does not wait. */
    void inline() {
        mayWait = false;
    }

    /**
     * Says that the link was reopened: the brick may have been switched off and on meanwhile and
     * its counters started again, so the next {@link #service} reads it before it sends anything.
     * Any thread (the link agent calls it as it reopens the link).
     */
    public void linkReopened() {
        polled = false;
    }

    /** @return where the driver reports what it reads */
    public FeedbackSink feedback() {
        return feedback;
    }

    /**
     * @return the execution action thread's cycle whose states the link side took last: a refusal
     *         during a service concerns the commands admitted up to it, and those running when it
     *         began; {@link Long#MAX_VALUE} when a flush did not say; 0 before it took any
     */
    public long servedCycle() {
        return handOff.servedCycle();
    }

    /**
     * One round: sends the published states and the link side's own stops, then polls. The first
     * round after the link was opened or {@linkplain #linkReopened reopened} polls before it sends
     * too, so that a rotation started in it counts from the brick's own reading.
     *
     * @return the round's work: 1 if it sent a batch, plus the motors the driver watches move
     * @throws IOException if the link failed: the states taken are sent with the next round
     * @throws RuntimeException if the brick refused them (a brick's error status): they are not sent
     *                          again, and the stops waiting for them fail with it
     */
    public int service() throws IOException {
        if (!polled) {
            // Read the brick before anything is sent: a rotation counts from where its motor's
            // counter stands when it starts, and a command given right after opening would
            // otherwise start before any reading, from 0, which a counter need not show (an NXT's
            // tacho count kept from before; the Intelligent Interface's impulse wheel, half a
            // tick); right after a reopen, from the reading before the loss, which a brick
            // switched off and on meanwhile no longer shows.
            driver.poll(feedback);
            polled = true;
        }
        handOff.take();
        for (MotorPort p : ports) {
            if (p.brakeAtLimit) {
                p.brakeAtLimit = false;
                if (p.draining == null) {
                    p.draining = MotorState.stopped(p.name, MotorState.StopMode.BRAKE);
                }
            }
        }
        if (timing.stopsOnLinkSide()) {
            anticipateStops();
        }
        // The batch as an unmodifiable list of its one or two states (a drive's wheels: one object
        // a batch, written at every change of every robot's drive), a list of its own beyond.
        MotorState first = null;
        MotorState second = null;
        List<MotorState> more = null;
        for (MotorPort p : ports) {
            MotorState s = p.draining;
            if (s == null) {
                continue;
            }
            if (!s.running() && s.equals(p.sent())) {
                p.draining = null; // the brick is stopped so already (it braked at its limit from here)
                continue;
            }
            if (first == null) {
                first = s;
            } else if (second == null) {
                second = s;
            } else {
                if (more == null) {
                    more = new ArrayList<>(ports.length);
                    more.add(first);
                    more.add(second);
                }
                more.add(s);
            }
        }
        List<MotorState> batch = more != null ? more : second != null ? List.of(first, second) : first != null ? List.of(first) : null;
        if (batch == null) {
            handOff.written(); // everything taken is what the brick does already
        } else {
            send(batch);
        }
        return driver.poll(feedback) + (batch == null ? 0 : 1);
    }

    /** Hands a batch to the driver, counting its states as sent and its rotations as started. */
    private void send(List<MotorState> batch) throws IOException {
        // The states count as sent from here on, so that a driver that reads the brick in the same
        // exchange (a pipelined poll) reports on these states, not the ones before; a rotation
        // counts from where the motor will be when the brick takes it.
        for (MotorPort p : ports) {
            MotorState s = p.draining;
            if (s == null) {
                continue;
            }
            MotorState previous = p.sent();
            if (s.running()) {
                MotorPort.Start was = p.start();
                long since = was != null && was.state() == previous ? was.sinceNanos() : Long.MIN_VALUE;
                double speed = previous == null ? 0 : predictor.actualDegreesPerSecond(previous);
                p.start(new MotorPort.Start(s, predictor.predictedDegrees(p, speed, since), Long.MAX_VALUE));
            }
            p.sentBefore = previous;
            p.sent(s);
        }
        try {
            driver.send(batch, feedback);
            handOff.written();
            long took = clock.nanoTime() - timing.actedNanosAgo();
            for (MotorPort p : ports) {
                MotorState s = p.draining;
                MotorPort.Start start = s == null ? null : p.start();
                if (start != null && start.state() == s) {
                    start.sent(took);
                }
            }
        } catch (IOException | RuntimeException e) {
            for (MotorPort p : ports) {
                if (p.draining != null) {
                    p.sent(p.sentBefore);
                }
            }
            // A refusal (RuntimeException: the brick answered with an error status) is not sent
            // again: it would be refused again, every cycle; the commands that wanted it fail with
            // it, and so do the stops waiting for it to be written.
            if (e instanceof RuntimeException r) {
                handOff.failPendingStops(r);
            } else {
                handOff.putBack();
            }
            throw e;
        } finally {
            for (MotorPort p : ports) {
                p.draining = null;
                p.sentBefore = null;
            }
        }
    }

    /**
     * Adds a stop to the batch for every limited rotation that reaches its target, by prediction,
     * before the link side's next chance to send, and marks it stopped at its limit; they go
     * together, at the mean of the moments each should be sent.
     */
    private void anticipateStops() {
        long next = timing.nextSendNanos(predictor.cycleNanos());
        long[] due = null;
        for (MotorPort p : ports) {
            MotorState s = p.sent();
            if (p.draining != null || s == null || !s.running() || Double.isInfinite(s.limitDegrees()) || !driver.hasEncoder(p.name)) {
                continue;
            }
            MotorPort.Start start = p.start();
            if (start == null || start.state() != s) {
                continue;
            }
            long eta = predictor.nanosToLimit(p, start, s);
            if (eta < next) {
                if (due == null) {
                    due = new long[ports.length];
                    Arrays.fill(due, -1);
                }
                due[p.index] = eta;
            }
        }
        if (due == null) {
            return;
        }
        long wait = (long) Arrays.stream(due).filter(d -> d >= 0).average().orElse(0);
        if (wait > 0 && mayWait) {
            // On the link agent's own thread (which the action side wakes whenever it publishes):
            // wait out the time.
            long until = clock.nanoTime() + wait;
            for (long left = wait; left > 0; left = until - clock.nanoTime()) {
                LockSupport.parkNanos(this, left);
            }
        }
        for (MotorPort p : ports) {
            if (due[p.index] >= 0) {
                p.draining = MotorState.stopped(p.name, MotorState.StopMode.BRAKE);
                p.stoppedAtLimit(p.sent());
            }
        }
    }

    /** What the driver reports, recorded in the ports' link-side state. */
    private final class Feedback implements FeedbackSink {
        @Override
        public void degrees(int portIndex, double degrees) {
            ports[portIndex].reading(degrees, clock.nanoTime() - timing.oneWayDelayNanos());
        }

        @Override
        public void degrees(String port, double degrees) {
            motors.port(port).reading(degrees, clock.nanoTime() - timing.oneWayDelayNanos());
        }

        @Override
        public void stoppedAtLimit(String port) {
            MotorPort p = motors.port(port);
            MotorState last = p.sent();
            if (last != null && last.running() && !Double.isInfinite(last.limitDegrees())) {
                p.stoppedAtLimit(last);
                if (last.stopMode() == MotorState.StopMode.BRAKE) {
                    p.brakeAtLimit = true;
                }
            }
        }
    }
}
