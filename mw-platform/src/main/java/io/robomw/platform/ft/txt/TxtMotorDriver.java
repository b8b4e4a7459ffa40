package io.robomw.platform.ft.txt;

import io.robomw.api.Clock;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.List;
import java.util.Map;

/**
 * The TXT's motor driver. The TXT is driven by one cyclic exchange that carries every output and
 * brings back every input and counter, so:
 * <ul>
 *   <li>{@link #send} only records each changed motor's wanted PWM (|speed| ÷
 *   {@link FtMotors#DEGREES_PER_SECOND_AT_FULL_POWER} × 512, forward on pwm[2i], reverse on
 *   pwm[2i+1]) and a new motor command: a rotation with a limit becomes the TXT's own distance
 *   command ({@code motor_dist} pulses, started by a new {@code motor_cmd_id}), so the controller
 *   stops the motor at the target without waiting for the link; two wheels started together at
 *   the same speed for the same rotation are also put in step ({@code motor_sync}). The
 *   {@link MotorPlatform}'s logic stops at the target too, whichever comes first;</li>
 *   <li>{@link #poll}, on the link side every round, sends the exchange (this is also the
 *   keep-alive) and turns the fast counters into encoder degrees.</li>
 * </ul>
 *
 * <h2>Encoders</h2>
 * A wheel's encoder is counted on its counter (see {@link TxtPorts#wheelCounters}),
 * {@code encoder_ticks_per_revolution} pulses per motor turn. The TXT counts pulses up whichever
 * way the motor turns, so each cycle's new pulses are signed by the direction the motor was last
 * driven in. Counters are never reset: the platform follows their increments, and starts again
 * from the next reading when a new session begins (the TXT may have restarted them). Distance
 * commands are used only when the wheel is counted on the counter of its own number, since that
 * is the counter the TXT's distance command watches. Actuator motors have no encoders here and
 * are stopped by time.
 *
 * <p>Threads: {@link #send} and {@link #poll} run on the link side;
 * {@link #exchangeNow} may also be called by a sensor read on a program thread. The output state
 * and counter bookkeeping are guarded by one lock.
 */
public final class TxtMotorDriver implements MotorDriver {

    private final TxtController controller;
    private final Clock clock;
    private final Map<String, Integer> counterOf;
    private final int ticksPerRevolution;
    private final Object lock = new Object();
    // Guarded by lock:
    private final int[] pwm = new int[TxtProtocol.OUTPUTS];
    private final int[] sync = new int[TxtProtocol.MOTORS];
    private final int[] dist = new int[TxtProtocol.MOTORS];
    private final int[] motorCmdId = new int[TxtProtocol.MOTORS];
    private final int[] counterCmdId = new int[TxtProtocol.COUNTERS];
    private final int[] direction = new int[TxtProtocol.MOTORS];
    private final int[] lastCount = new int[TxtProtocol.COUNTERS];
    private final long[] pulses = new long[TxtProtocol.MOTORS];
    private long session = -1;
    private volatile Inputs inputs;

    /**
     * The inputs of the last exchange.
     *
     * @param values     I1..I8 as the TXT reported them
     * @param generation the configuration generation they were read in
     * @param atNanos    the platform's clock time when they arrived
     */
    record Inputs(int[] values, int generation, long atNanos) {
    }

    /**
     * @param config      the platform configuration: motor ports M1..M4, which counter counts each wheel, and its pulses per motor turn
     * @param controller  the TXT
     * @throws IllegalArgumentException if a motor port is not M1..M4 or a counter is not C1..C4
     */
    public TxtMotorDriver(PlatformConfig config, TxtController controller) {
        this.controller = controller;
        this.clock = config.clock();
        for (String port : config.motorPorts()) {
            TxtPorts.motor(port);
        }
        this.counterOf = TxtPorts.wheelCounters(config.motors(), config.source());
        this.ticksPerRevolution = config.wheels().stream().mapToInt(MotorChannel::encoderTicksPerRevolution).max().orElse(0);
    }

    @Override
    public boolean hasEncoder(String port) {
        return ticksPerRevolution > 0 && counterOf.containsKey(port);
    }

    /**
     * @param degreesPerSecond a signed motor speed
     * @return the TXT PWM value for its magnitude, 0..512; at least 1 for any speed other than 0
     */
    static int pwm(double degreesPerSecond) {
        if (degreesPerSecond == 0) {
            return 0;
        }
        long p = Math.round(Math.abs(FtMotors.duty(degreesPerSecond)) * TxtProtocol.PWM_MAX);
        return (int) Math.max(1, Math.min(TxtProtocol.PWM_MAX, p));
    }

    /**
     * @param degrees            motor degrees still to turn
     * @param ticksPerRevolution encoder pulses per motor turn
     * @return the distance command for it, in pulses (at least 1), or 0 if it does not fit the s16 field
     */
    static int distancePulses(double degrees, int ticksPerRevolution) {
        long p = Math.max(1, Math.round(Math.abs(degrees) * ticksPerRevolution / 360.0));
        return p > Short.MAX_VALUE ? 0 : (int) p;
    }

    /** Whether the TXT's distance command can stop this motor: it is counted on the counter of its own number. */
    private boolean distanceCapable(String port) {
        Integer counter = counterOf.get(port);
        return ticksPerRevolution > 0 && counter != null && counter == TxtPorts.motor(port);
    }

    @Override
    public LinkTiming timing() {
        return LinkTiming.NONE;
    }

    @Override
    public void send(List<MotorState> motors, FeedbackSink feedback) {
        boolean pair = motors.size() == 2 && motors.get(0).running() && motors.get(1).running()
                && motors.get(0).degreesPerSecond() == motors.get(1).degreesPerSecond()
                && motors.get(0).limitDegrees() == motors.get(1).limitDegrees() && Double.isFinite(motors.get(0).limitDegrees())
                && distanceCapable(motors.get(0).port()) && distanceCapable(motors.get(1).port());
        synchronized (lock) {
            for (int k = 0; k < motors.size(); k++) {
                MotorState m = motors.get(k);
                int i = TxtPorts.motor(m.port());
                int p = pwm(m.degreesPerSecond());
                pwm[2 * i] = m.degreesPerSecond() > 0 ? p : 0;
                pwm[2 * i + 1] = m.degreesPerSecond() < 0 ? p : 0;
                boolean limited = m.running() && Double.isFinite(m.limitDegrees()) && distanceCapable(m.port());
                dist[i] = limited ? distancePulses(m.limitDegrees(), ticksPerRevolution) : 0;
                sync[i] = pair && dist[i] != 0 ? TxtPorts.motor(motors.get(1 - k).port()) + 1 : 0;
                motorCmdId[i] = (motorCmdId[i] + 1) & TxtProtocol.CMD_ID_MASK;
            }
        }
    }

    /**
     * Runs the exchange.
     *
     * @return the motors driven (a PWM value other than 0)
     */
    @Override
    public int poll(FeedbackSink feedback) throws IOException {
        exchangeNow(feedback);
        int driven = 0;
        synchronized (lock) {
            for (int i = 0; i < TxtProtocol.MOTORS; i++) {
                if (pwm[2 * i] != 0 || pwm[2 * i + 1] != 0) {
                    driven++;
                }
            }
        }
        return driven;
    }

    /**
     * Runs one exchange now: sends the current outputs, reports the encoders and publishes the
     * inputs. Called every round by the link side, and by a sensor read that finds the inputs
     * stale.
     *
     * @param feedback where the encoders go
     * @throws IOException if the link failed; the published inputs are then cleared
     */
    void exchangeNow(FeedbackSink feedback) throws IOException {
        synchronized (lock) {
            TxtProtocol.Exchange request = new TxtProtocol.Exchange(pwm, sync, dist, motorCmdId, counterCmdId, 0, 0, 0);
            TxtController.Reading reading;
            try {
                reading = controller.exchange(request);
            } catch (IOException | RuntimeException e) {
                inputs = null;
                throw e;
            }
            count(reading, feedback);
            for (int i = 0; i < TxtProtocol.MOTORS; i++) {
                int driven = pwm[2 * i] - pwm[2 * i + 1];
                if (driven != 0) {
                    direction[i] = Integer.signum(driven);
                }
            }
            inputs = new Inputs(reading.reply().input(), reading.generation(), clock.nanoTime());
        }
    }

    /** @return how long ago, on the platform's clock, inputs read at {@code atNanos} were read */
    long ageNanos(Inputs in) {
        return clock.nanoTime() - in.atNanos();
    }

    /** @return the inputs of the last exchange, or {@code null} if it failed or none ran yet */
    Inputs inputs() {
        return inputs;
    }

    /**
     * Adds the pulses counted since the last reading, signed by the direction each motor was
     * driven in until this exchange, and reports the wheels' degrees. Called with the lock held.
     */
    private void count(TxtController.Reading reading, FeedbackSink feedback) {
        boolean rebase = reading.session() != session;
        session = reading.session();
        int[] values = reading.reply().counterValue();
        for (Map.Entry<String, Integer> e : counterOf.entrySet()) {
            int motor = TxtPorts.motor(e.getKey());
            int c = e.getValue();
            if (!rebase) {
                int delta = (short) (values[c] - lastCount[c]);
                if (delta < 0) {
                    // The counter only counts up: it was reset behind our back; count from 0.
                    delta = Math.max(0, values[c]);
                }
                pulses[motor] += (long) delta * (direction[motor] < 0 ? -1 : 1);
            }
            lastCount[c] = values[c];
            if (ticksPerRevolution > 0) {
                feedback.degrees(e.getKey(), pulses[motor] * 360.0 / ticksPerRevolution);
            }
        }
    }
}
