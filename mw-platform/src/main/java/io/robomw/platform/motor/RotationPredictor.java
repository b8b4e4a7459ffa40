package io.robomw.platform.motor;

import io.robomw.api.Clock;

/**
 * Where a motor will be when a command sent now reaches the brick: the overshoot prediction both
 * sides of the motor platform share, fed by the driver's {@link LinkTiming}.
 *
 * <p>A reading is a sample the brick took one link delay ({@link LinkTiming#oneWayDelayNanos()})
 * before it arrived, and a stop sent now reaches the brick a command delay
 * ({@link LinkTiming#commandDelayNanos()}) later: so the prediction moves the last reading on by
 * the commanded speed over its age and the command's delay (together at most three cycles and
 * those delays, so a reading that stopped coming is not extrapolated without end); stopping on the
 * bare reading would overshoot by both. A coarse encoder ({@link LinkTiming#encoderResolutionDegrees})
 * is believed within half a count, the motor's own speed since it started deciding inside it; a
 * brick that turns motors at stepped speeds is predicted with its step's speed
 * ({@link LinkTiming#actualDegreesPerSecond}). Time is the platform's injected clock.
 *
 * <p>Thread-safe: it reads each port's state through its release/acquire fields and sequence lock.
 */
final class RotationPredictor {

    private final Clock clock;
    private final LinkTiming timing;
    private volatile long cycleNanos;

    /**
     * @param clock      the platform's clock
     * @param timing     the driver's link timing
     * @param cycleNanos the execution action thread's period
     */
    RotationPredictor(Clock clock, LinkTiming timing, long cycleNanos) {
        this.clock = clock;
        this.timing = timing;
        this.cycleNanos = cycleNanos;
    }

    /** @return the execution action thread's period, nanoseconds */
    long cycleNanos() {
        return cycleNanos;
    }

    /** @param nanos the execution action thread's period */
    void cycleNanos(long nanos) {
        cycleNanos = nanos;
    }

    /** @return the driver's link timing */
    LinkTiming timing() {
        return timing;
    }

    /** @return the speed the brick turns a motor at in this state (a stepped speed, on a brick that has steps) */
    double actualDegreesPerSecond(MotorState state) {
        return timing.actualDegreesPerSecond(state);
    }

    /** @return how far the rotation a port last started has turned by the time a command sent now reaches the brick; 0 before one */
    double turned(MotorPort p) {
        MotorPort.Start start = p.start();
        return start == null ? 0 : turned(p, start);
    }

    /** @return how far a rotation has turned, from where it started, by the time a command sent now reaches the brick */
    double turned(MotorPort port, MotorPort.Start start) {
        double speed = timing.actualDegreesPerSecond(start.state());
        long since = start.sinceNanos(); // once: the link side sets it when the driver has sent the start
        double predicted = predictedDegrees(port, speed, since);
        double resolution = timing.encoderResolutionDegrees(port.name);
        long now = clock.nanoTime();
        if (resolution > 0 && since <= now) {
            // A coarse encoder (a reading is the nearest count): believe the motor's own speed since
            // it started, within the half count either side of the reading that the count allows.
            double byTime = start.degrees() + speed * (now + timing.commandDelayNanos() - since) / 1e9;
            predicted = Math.max(predicted - resolution / 2, Math.min(predicted + resolution / 2, byTime));
        }
        return Math.abs(predicted - start.degrees());
    }

    /**
     * Where the motor will be when a command sent now reaches the brick: the last reading moved on
     * by the speed for the reading's age (or since the motor started turning, if later) and the
     * command's delay, together at most three cycles and those delays.
     *
     * @param degreesPerSecond the speed it turns at
     * @param turningSince     since when it turns at that speed ({@link Long#MIN_VALUE}: as long as
     *                         the reading is old; {@link Long#MAX_VALUE}: not yet)
     * @return degrees; 0 before the first reading
     */
    double predictedDegrees(MotorPort port, double degreesPerSecond, long turningSince) {
        int version;
        double degrees;
        long at;
        do {
            version = port.readingBegin();
            degrees = port.readingDegreesRaw();
            at = port.readingAtNanosRaw();
        } while (!port.readingWhole(version) && spin());
        if (version == 0) {
            return 0.0; // no reading yet
        }
        long now = clock.nanoTime();
        if (turningSince > now) {
            return degrees;
        }
        long delay = timing.commandDelayNanos();
        long from = Math.max(at, turningSince);
        long ahead = Math.min(Math.max(0, now - from) + delay, 3 * cycleNanos + 4 * timing.oneWayDelayNanos() + delay);
        return degrees + degreesPerSecond * ahead / 1e9;
    }

    /** @return true, after a spin-wait hint (while a reading is being written) */
    private static boolean spin() {
        Thread.onSpinWait();
        return true;
    }

    /**
     * @return how long until a running limited rotation reaches its limit, by prediction, from the
     *         moment a command sent now reaches the brick (0 if past it; {@link Long#MAX_VALUE} for a
     *         motor that does not turn)
     */
    long nanosToLimit(MotorPort p, MotorPort.Start start, MotorState sent) {
        double remaining = sent.limitDegrees() - turned(p, start);
        double speed = Math.abs(timing.actualDegreesPerSecond(sent));
        return speed == 0 ? Long.MAX_VALUE : (long) Math.max(0, remaining / speed * 1e9);
    }
}
