package io.robomw.sim.emulator.nxt;

import io.robomw.platform.nxt.NxtTelegram;

/**
 * The NXT firmware's three motor outputs as the emulator runs them: what the output module's
 * IOMap holds (the fields GETOUTPUTSTATE reports) and what {@code d_output.c} keeps per motor to
 * end a rotation at its tacho limit. Written from reading the firmware (LEGO 1.29, as
 * {@code dlech/nxt-firmware} @99b10c1 has it: {@code c_cmd.c} SETOUTPUTSTATE and
 * UPDATE_RESET_COUNT, {@code c_output.c} {@code cOutputCtrl}, {@code d_output.c}
 * {@code dOutputSetSpeed}, {@code dOutputSetTachoLimit}, {@code dOutputResetTachoLimit},
 * {@code dOutputTachoLimitControl}, {@code dOutputSyncTachoLimitControl},
 * {@code dOutputMotorIdleControl}, {@code dOutputSyncMotorPosition}).
 *
 * <h2>What the firmware does, and so this model</h2>
 * <ul>
 *   <li><b>Three counters.</b> The tacho count ({@code CurrentCaptureCount}) counts from the last
 *   UPDATE_RESET_COUNT (0x21) or program start, <em>not</em> from each SETOUTPUTSTATE; the block
 *   tacho count from the last RESETMOTORPOSITION relative, the rotation count from the last
 *   RESETMOTORPOSITION absolute.</li>
 *   <li><b>A SETOUTPUTSTATE</b> is applied in {@code cOutputCtrl}'s order: speed (only with
 *   MOTORON: RUNNING sets the set and target speed, IDLE lets the motor coast), mode (without
 *   MOTORON the motor goes idle), then the tacho limit.</li>
 *   <li><b>A tacho limit is added to the motor's running target</b>
 *   ({@code MotorTachoCountToRun += limit}, or {@code -=} when the new speed is negative; with
 *   speed 0, by the sign of the old target speed). Limit 0 means run forever, and while a motor
 *   runs forever its target follows its tacho count. So a limit counts from where the last limited
 *   rotation was to end, not from where the motor is: a rotation pre-empted before its end leaves
 *   its remainder in the target, and the next limit is added to that. Only UPDATE_RESET_COUNT
 *   zeroes the count and the target (and, for a synchronised motor, its partner's).</li>
 *   <li><b>The limit is reached</b> when the tacho count passes the target in the direction of
 *   the set speed; for two synchronised motors with turn ratio 0, when either of them does, and
 *   both stop. The output then goes idle: the motor coasts, driven with a power that falls by 1
 *   each millisecond ({@code dOutputMotorIdleControl}), so it overshoots the limit by a few
 *   degrees, more at high power.</li>
 *   <li><b>Synchronisation</b> keeps the difference of the two motors' <em>block</em> tacho
 *   counts at zero: a driver that does not reset the block counts before a synchronised move makes
 *   the pair work off whatever difference an earlier turn left.</li>
 * </ul>
 * Simplifications: regulation reaches the set speed at once (power P turns at P % of
 * {@link NxtTelegram#DEGREES_PER_SECOND_AT_FULL_POWER}); RAMPUP and RAMPDOWN run like RUNNING;
 * the model advances once per world step instead of once per millisecond, landing a rotation on
 * its limit within the step in which it reaches it.
 *
 * <p>Not thread-safe: the emulator guards it with its firmware lock.
 */
final class NxtOutputs {

    /** The NXT's motor outputs A, B, C. */
    static final int COUNT = 3;

    /** Degrees per second of regulation correction per degree that two synchronised motors are apart. */
    private static final double SYNC_GAIN_PER_SECOND = 25;
    /** The firmware's coasting power falls by this much per second (1 per 1 ms tick). */
    private static final double IDLE_POWER_DECAY_PER_SECOND = 1000;

    private final Output[] outputs = new Output[COUNT];

    /** One output: its IOMap fields and its {@code d_output} motor data. */
    static final class Output {
        final String port;
        final boolean connected;
        // IOMap fields, as the last SETOUTPUTSTATE wrote them (GETOUTPUTSTATE reports these)
        int power;
        int mode;
        int regulationMode;
        int turnRatio;
        long tachoLimit;
        // d_output motor data
        int runState = NxtTelegram.RUN_IDLE;
        int regulation = NxtTelegram.REGULATION_IDLE;
        int setSpeed;
        int targetSpeed;
        double drivenPower;
        long countToRun;
        boolean runForever = true;
        double degrees;
        double tachoZero;
        double blockZero;
        double rotationZero;
        double speed;

        Output(String port, boolean connected) {
            this.port = port;
            this.connected = connected;
        }

        /** @return the tacho count, degrees since the last UPDATE_RESET_COUNT */
        double tachoCount() {
            return degrees - tachoZero;
        }

        /** @return the tacho count as the firmware counts it, in whole degrees */
        long count() {
            return Math.round(tachoCount());
        }

        /** @return the block tacho count */
        double blockCount() {
            return degrees - blockZero;
        }

        /** @return the rotation count */
        double rotationCount() {
            return degrees - rotationZero;
        }

        boolean synchronised() {
            return regulation == NxtTelegram.REGULATION_SYNC;
        }
    }

    /**
     * @param connected whether a motor is plugged into each output, A first
     */
    NxtOutputs(boolean[] connected) {
        for (int i = 0; i < COUNT; i++) {
            outputs[i] = new Output(String.valueOf((char) ('A' + i)), connected[i]);
        }
    }

    /**
     * @param index 0..2
     * @return the output
     */
    Output get(int index) {
        return outputs[index];
    }

    /**
     * Applies a SETOUTPUTSTATE to one output, as {@code c_cmd.c} and then {@code cOutputCtrl} do.
     */
    void setOutputState(int index, int power, int mode, int regulationMode, int turnRatio, int runState, long tachoLimit) {
        Output o = outputs[index];
        o.power = power;
        o.mode = mode;
        o.regulationMode = regulationMode;
        o.turnRatio = turnRatio;
        o.tachoLimit = tachoLimit;
        boolean motorOn = (mode & NxtTelegram.MODE_MOTORON) != 0;
        if (motorOn) {
            setSpeed(o, runState, power, turnRatio);
        }
        if (motorOn) {
            o.regulation = (mode & NxtTelegram.MODE_REGULATED) != 0 ? regulationMode : NxtTelegram.REGULATION_IDLE;
        } else {
            setSpeed(o, NxtTelegram.RUN_IDLE, 0, 0);
            o.regulation = NxtTelegram.REGULATION_IDLE;
        }
        setTachoLimit(o, tachoLimit);
    }

    /** {@code dOutputSetSpeed}, with RAMPUP and RAMPDOWN run as RUNNING and HOLD as RUNNING at speed 0. */
    private static void setSpeed(Output o, int runState, int speed, int turnRatio) {
        boolean changes = o.setSpeed != speed || o.runState != runState || runState == NxtTelegram.RUN_IDLE || o.turnRatio != turnRatio;
        if (!changes) {
            return;
        }
        if (runState == NxtTelegram.RUN_IDLE) {
            o.regulation = NxtTelegram.REGULATION_IDLE;
            o.runState = NxtTelegram.RUN_IDLE;
            return;
        }
        o.setSpeed = speed;
        o.targetSpeed = speed;
        o.runState = NxtTelegram.RUN_RUNNING;
    }

    /** {@code dOutputSetTachoLimit}: the limit is added to the running target. */
    private static void setTachoLimit(Output o, long limit) {
        if (limit == 0) {
            o.runForever = true;
            return;
        }
        o.runForever = false;
        boolean forward = o.setSpeed != 0 ? o.setSpeed > 0 : o.targetSpeed > 0;
        o.countToRun += forward ? limit : -limit;
    }

    /**
     * UPDATE_RESET_COUNT ({@code dOutputResetTachoLimit}): zeroes the tacho count and the target
     * (a synchronised motor's partner's too), and ends running forever.
     *
     * @param index the output
     */
    void resetCount(int index) {
        Output o = outputs[index];
        if (o.synchronised()) {
            Output partner = partnerOf(o);
            if (partner != null) {
                zeroCount(partner);
            }
        }
        zeroCount(o);
        o.runForever = false;
    }

    private static void zeroCount(Output o) {
        o.tachoZero = o.degrees;
        o.countToRun = 0;
    }

    /**
     * RESETMOTORPOSITION.
     *
     * @param index    the output
     * @param relative true: the block tacho count; false: the rotation count
     */
    void resetPosition(int index, boolean relative) {
        Output o = outputs[index];
        if (relative) {
            o.blockZero = o.degrees;
        } else {
            o.rotationZero = o.degrees;
        }
    }

    /**
     * One world step of {@code dOutputCtrl}: the tacho limit control of running outputs, idle
     * control (coasting) of idle ones, then the speeds the motors turn at, with synchronised pairs
     * kept in step.
     *
     * @param degrees     each output's shaft rotation now
     * @param stepSeconds the world's step
     * @return each output's speed for the next step, degrees per second
     */
    double[] step(double[] degrees, double stepSeconds) {
        for (int i = 0; i < COUNT; i++) {
            outputs[i].degrees = degrees[i];
        }
        for (Output o : outputs) {
            if (!o.connected) {
                continue;
            }
            if (o.runState == NxtTelegram.RUN_RUNNING) {
                limitControl(o);
            }
        }
        double[] speeds = new double[COUNT];
        for (Output o : outputs) {
            if (!o.connected) {
                o.speed = 0;
                continue;
            }
            if (o.runState == NxtTelegram.RUN_IDLE) {
                o.drivenPower = towardsZero(o.drivenPower, IDLE_POWER_DECAY_PER_SECOND * stepSeconds);
                o.setSpeed = (int) towardsZero(o.setSpeed, IDLE_POWER_DECAY_PER_SECOND * stepSeconds);
                o.targetSpeed = (int) towardsZero(o.targetSpeed, IDLE_POWER_DECAY_PER_SECOND * stepSeconds);
            } else {
                o.drivenPower = o.setSpeed;
            }
            o.speed = o.drivenPower / 100.0 * NxtTelegram.DEGREES_PER_SECOND_AT_FULL_POWER * turnFactor(o);
        }
        keepPairInStep();
        for (Output o : outputs) {
            if (o.runState == NxtTelegram.RUN_RUNNING && !o.runForever && o.speed != 0) {
                o.speed = landOnTarget(o, stepSeconds);
            }
        }
        for (int i = 0; i < COUNT; i++) {
            speeds[i] = outputs[i].speed;
        }
        return speeds;
    }

    /** {@code dOutputTachoLimitControl} for a running output. */
    private void limitControl(Output o) {
        if (o.runForever) {
            if (o.targetSpeed != 0) {
                o.countToRun = o.count();
            }
            return;
        }
        Output partner = o.synchronised() ? partnerOf(o) : null;
        if (partner != null) {
            syncLimitControl(o, partner);
            return;
        }
        if ((o.setSpeed > 0 && o.count() >= o.countToRun) || (o.setSpeed < 0 && o.count() <= o.countToRun)) {
            o.runState = NxtTelegram.RUN_IDLE;
            o.regulation = NxtTelegram.REGULATION_IDLE;
        }
    }

    /**
     * {@code dOutputSyncTachoLimitControl}: with turn ratio 0, the pair stops when either motor
     * passes its target; with a turn ratio, the one the ratio slows is watched, and the other takes
     * over its count and target.
     */
    private static void syncLimitControl(Output one, Output two) {
        if (one.turnRatio == 0) {
            boolean reached = one.setSpeed > 0
                    ? one.count() >= one.countToRun || two.count() >= two.countToRun
                    : one.setSpeed < 0 && (one.count() <= one.countToRun || two.count() <= two.countToRun);
            if (reached) {
                one.runState = NxtTelegram.RUN_IDLE;
                two.runState = NxtTelegram.RUN_IDLE;
            }
            return;
        }
        Output watched;
        boolean forward;
        if (one.turnRatio > 0) {
            forward = two.targetSpeed >= 0;
            watched = forward ? two : one;
        } else {
            forward = one.targetSpeed >= 0;
            watched = forward ? one : two;
        }
        boolean reached = forward ? watched.count() >= watched.countToRun : watched.count() <= watched.countToRun;
        if (reached) {
            Output other = watched == one ? two : one;
            one.runState = NxtTelegram.RUN_IDLE;
            two.runState = NxtTelegram.RUN_IDLE;
            other.tachoZero = other.degrees - watched.tachoCount();
            other.countToRun = watched.countToRun;
        }
    }

    /** The other output in synchronised regulation, the first found from A, as the firmware looks for it. */
    private Output partnerOf(Output o) {
        for (Output other : outputs) {
            if (other != o && other.synchronised()) {
                return other;
            }
        }
        return null;
    }

    /**
     * The turn ratio of a synchronised pair: the first motor runs at full, the second at
     * 1 − turn/50 (−1 at 100), or the other way round for a negative ratio.
     */
    private double turnFactor(Output o) {
        if (!o.synchronised() || o.turnRatio == 0) {
            return 1;
        }
        boolean first = true;
        for (Output other : outputs) {
            if (other == o) {
                break;
            }
            first &= !other.synchronised();
        }
        double t = o.turnRatio;
        if (t > 0) {
            return first ? 1 : 1 - t / 50;
        }
        return first ? 1 + t / 50 : 1;
    }

    /**
     * {@code dOutputSyncMotorPosition} with turn ratio 0: the regulation works off the difference
     * of the two block tacho counts, slowing the motor ahead and speeding up the one behind.
     */
    private void keepPairInStep() {
        Output a = null;
        Output b = null;
        for (Output o : outputs) {
            if (o.connected && o.synchronised() && o.turnRatio == 0 && o.runState == NxtTelegram.RUN_RUNNING && o.speed != 0) {
                if (a == null) {
                    a = o;
                } else if (b == null) {
                    b = o;
                }
            }
        }
        if (a == null || b == null) {
            return;
        }
        double correction = SYNC_GAIN_PER_SECOND * (a.blockCount() - b.blockCount());
        a.speed -= correction;
        b.speed += correction;
    }

    /**
     * The firmware checks the limit every millisecond; the model steps more coarsely, so a motor
     * that would pass its target within this step is slowed to arrive on it at the step's end.
     */
    private static double landOnTarget(Output o, double stepSeconds) {
        double left = o.countToRun - o.tachoCount();
        if (o.speed > 0 && left > 0) {
            return Math.min(o.speed, left / stepSeconds);
        }
        if (o.speed < 0 && left < 0) {
            return Math.max(o.speed, left / stepSeconds);
        }
        return o.speed;
    }

    private static double towardsZero(double value, double by) {
        return value > 0 ? Math.max(0, value - by) : Math.min(0, value + by);
    }

    /** Stops every output at once, as a brick that is switched off. */
    void halt() {
        for (Output o : outputs) {
            o.power = 0;
            o.setSpeed = 0;
            o.targetSpeed = 0;
            o.drivenPower = 0;
            o.speed = 0;
            o.runState = NxtTelegram.RUN_IDLE;
            o.regulation = NxtTelegram.REGULATION_IDLE;
        }
    }
}
