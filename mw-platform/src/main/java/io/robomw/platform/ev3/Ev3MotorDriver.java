package io.robomw.platform.ev3;

import io.robomw.api.Clock;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.List;

/**
 * The EV3's motor driver. Each batch of motor states becomes one direct command, so motors
 * started together start within the same firmware cycle:
 * <ul>
 *   <li>a move with a rotation limit: opOUTPUT_STEP_SPEED with the limit as STEP2 (no ramps) and
 *   brake, so the brick stops the motor at the limit by itself;</li>
 *   <li>a continuous run: opOUTPUT_SPEED, then opOUTPUT_START;</li>
 *   <li>speed 0: opOUTPUT_STOP, braking or coasting as the state says.</li>
 * </ul>
 * Encoders are read at every poll, all motors in one direct command: opOUTPUT_GET_COUNT per motor
 * into its own 4 global bytes; a poll counts the motors that run or stopped less than
 * {@link #SETTLE_NANOS} ago as moving. The counts are zeroed (opOUTPUT_CLR_COUNT) when the robot
 * opens. The link has no timing of its own to give ({@link LinkTiming#NONE}).
 *
 * <p>Speeds are regulated percentages: {@code degrees per second / }{@value #DEGREES_PER_SECOND_AT_FULL_SPEED}
 * {@code × 100}, rounded, clamped to ±100, and at least ±1 for a turning motor (0 would stand it still).
 */
public final class Ev3MotorDriver implements MotorDriver {

    /**
     * Speed of an EV3 large motor at regulated speed 100, degrees per second (its no-load speed is
     * about 170 rpm). The driver and the brick emulator both use this constant.
     */
    public static final double DEGREES_PER_SECOND_AT_FULL_SPEED = 1050;

    /** How long a stopped motor still counts as moving (its coasting shows in the encoder). */
    static final long SETTLE_NANOS = 300_000_000L;

    private final Ev3Brick brick;
    private final Clock clock;
    private final List<String> ports;
    private final Ev3Command getCounts;
    // By port index; link side only: each motor's last state, and when it was sent.
    private final MotorState[] commanded;
    private final long[] changedAt;

    /**
     * @param config the platform configuration (motor ports among A, B, C, D)
     * @param brick  the brick
     * @throws IllegalArgumentException if a motor port is not one of A..D
     */
    public Ev3MotorDriver(PlatformConfig config, Ev3Brick brick) {
        this.brick = brick;
        this.clock = config.clock();
        this.ports = List.copyOf(config.motorPorts());
        this.commanded = new MotorState[ports.size()];
        this.changedAt = new long[ports.size()];
        Ev3Command.Builder b = Ev3Command.withReply(4 * ports.size());
        for (int i = 0; i < ports.size(); i++) {
            b.outputGetCount(Ev3Ports.outputNumber(ports.get(i)), 4 * i);
        }
        this.getCounts = ports.isEmpty() ? null : b.build();
    }

    /**
     * @param degreesPerSecond a motor speed
     * @return the EV3's regulated speed for it, -100..100; never 0 for a speed that is not 0
     */
    public static int speedPercent(double degreesPerSecond) {
        if (degreesPerSecond == 0) {
            return 0;
        }
        long p = Math.round(Math.abs(degreesPerSecond) / DEGREES_PER_SECOND_AT_FULL_SPEED * 100);
        int magnitude = (int) Math.max(1, Math.min(100, p));
        return degreesPerSecond < 0 ? -magnitude : magnitude;
    }

    /**
     * @param motors motor states
     * @return the direct command that applies them (no reply data, but a reply, so a refusal is seen)
     */
    static Ev3Command commandFor(List<MotorState> motors) {
        Ev3Command.Builder b = Ev3Command.withReply(0);
        for (MotorState m : motors) {
            int nos = Ev3Ports.outputBit(m.port());
            if (!m.running()) {
                b.outputStop(nos, m.stopMode());
                continue;
            }
            int speed = speedPercent(m.degreesPerSecond());
            if (Double.isInfinite(m.limitDegrees())) {
                b.outputSpeed(nos, speed).outputStart(nos);
            } else {
                int limit = (int) Math.max(1, Math.min(Integer.MAX_VALUE, Math.round(Math.abs(m.limitDegrees()))));
                b.outputStepSpeed(nos, speed, 0, limit, 0, MotorState.StopMode.BRAKE);
            }
        }
        return b.build();
    }

    @Override
    public LinkTiming timing() {
        return LinkTiming.NONE;
    }

    @Override
    public void send(List<MotorState> motors, FeedbackSink feedback) throws IOException {
        if (motors.isEmpty()) {
            return;
        }
        brick.request(commandFor(motors));
        long now = clock.nanoTime();
        for (MotorState m : motors) {
            int i = ports.indexOf(m.port());
            commanded[i] = m;
            changedAt[i] = now;
        }
    }

    @Override
    public int poll(FeedbackSink feedback) throws IOException {
        if (getCounts == null) {
            return 0;
        }
        Ev3Reply reply = brick.request(getCounts);
        long now = clock.nanoTime();
        int moving = 0;
        for (int i = 0; i < ports.size(); i++) {
            feedback.degrees(i, reply.data32(4 * i));
            MotorState m = commanded[i];
            if (m != null && (m.running() || now - changedAt[i] < SETTLE_NANOS)) {
                moving++;
            }
        }
        return moving;
    }

    /**
     * Zeroes every motor's tacho count, so encoders count from the platform's start.
     *
     * @throws IOException if the link failed
     */
    void clearCounts() throws IOException {
        int nos = 0;
        for (String port : ports) {
            nos |= Ev3Ports.outputBit(port);
        }
        if (nos != 0) {
            brick.request(Ev3Command.withReply(0).outputClrCount(nos).build());
        }
    }
}
