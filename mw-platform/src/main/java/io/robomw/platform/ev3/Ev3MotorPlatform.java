package io.robomw.platform.ev3;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.List;

/**
 * The EV3's motor platform. Each batch of motor states becomes one direct command, so motors
 * started together start within the same firmware cycle:
 * <ul>
 *   <li>a move with a rotation limit: opOUTPUT_STEP_SPEED with the limit as STEP2 (no ramps) and
 *   brake, so the brick stops the motor at the limit by itself;</li>
 *   <li>a continuous run: opOUTPUT_SPEED, then opOUTPUT_START;</li>
 *   <li>speed 0: opOUTPUT_STOP, braking or coasting as the state says.</li>
 * </ul>
 * Encoders are read once per cycle, all motors in one direct command: opOUTPUT_GET_COUNT per motor
 * into its own 4 global bytes. The counts are zeroed (opOUTPUT_CLR_COUNT) when the robot opens.
 *
 * <p>Speeds are regulated percentages: {@code degrees per second / }{@value #DEGREES_PER_SECOND_AT_FULL_SPEED}
 * {@code × 100}, rounded, clamped to ±100, and at least ±1 for a turning motor (0 would stand it still).
 */
public final class Ev3MotorPlatform extends GenericMotorPlatform {

    /**
     * Speed of an EV3 large motor at regulated speed 100, degrees per second (its no-load speed is
     * about 170 rpm). The driver and the brick emulator both use this constant.
     */
    public static final double DEGREES_PER_SECOND_AT_FULL_SPEED = 1050;

    private final Ev3Brick brick;
    private final List<String> ports;
    private final Ev3Command getCounts;

    /**
     * @param config the platform configuration (motor ports among A, B, C, D)
     * @param brick  the brick
     * @throws IllegalArgumentException if a motor port is not one of A..D
     */
    public Ev3MotorPlatform(PlatformConfig config, Ev3Brick brick) {
        super(config.robotName(), config.clock(), config.motorPorts());
        this.brick = brick;
        this.ports = List.copyOf(config.motorPorts());
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
    protected void runImpl(List<MotorState> motors) throws IOException {
        if (!motors.isEmpty()) {
            brick.request(commandFor(motors));
        }
    }

    @Override
    protected void pollFeedback() throws IOException {
        if (getCounts == null) {
            return;
        }
        Ev3Reply reply = brick.request(getCounts);
        for (int i = 0; i < ports.size(); i++) {
            reportDegrees(ports.get(i), reply.data32(4 * i));
        }
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
