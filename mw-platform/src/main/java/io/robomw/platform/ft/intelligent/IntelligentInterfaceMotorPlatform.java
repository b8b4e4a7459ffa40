package io.robomw.platform.ft.intelligent;

import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

import static io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram.ANALOG_EX;
import static io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram.ANALOG_EY;

/**
 * The Intelligent Interface's motor platform. The interface only switches motors on and off, has
 * no encoders, and stops its motors 300 ms after the last command, so:
 * <ul>
 *   <li>{@link #runImpl} only records each motor's wanted duty (speed ÷ full speed);</li>
 *   <li>{@link #pollFeedback}, on the link thread every cycle whatever the application does, sends
 *   the motor byte (keeping the interface alive) with each motor on or off for this cycle by a
 *   sigma-delta over its duty (so 40 % duty is on in 2 cycles of 5), alternating the EX and EY
 *   reads, and reads the inputs back;</li>
 *   <li>a limited move creeps (at most 25 % duty) over its last three ticks, and the link thread
 *   stops it itself when its count reaches the limit (as a brick with a tacho limit would), so
 *   neither a busy action thread nor a late poll lets it run on;</li>
 *   <li>a wheel's distance is counted on the digital input its description names
 *   ({@code counter: E1}): every transition of the impulse wheel's switch is one tick,
 *   {@code encoder_ticks_per_revolution} ticks per motor turn, signed by the direction the motor
 *   was driven in.</li>
 * </ul>
 * Positive speeds turn a motor clockwise ("right", bits {@code 10}).
 */
public final class IntelligentInterfaceMotorPlatform extends GenericMotorPlatform {

    private final BrickChannel channel;
    private final int ticksPerRevolution;
    private final double[] duty = new double[IntelligentInterfaceTelegram.MOTORS];
    private final double[] accumulator = new double[IntelligentInterfaceTelegram.MOTORS];
    private final int[] lastDirection = new int[IntelligentInterfaceTelegram.MOTORS];
    private final Map<String, Integer> counterOf = new HashMap<>();
    private final long[] ticks = new long[IntelligentInterfaceTelegram.MOTORS];
    private final double[] limit = new double[IntelligentInterfaceTelegram.MOTORS];
    private final long[] ticksAtStart = new long[IntelligentInterfaceTelegram.MOTORS];

    /** Duty of the last {@link #CREEP_TICKS} ticks of a limited move. */
    static final double CREEP_DUTY = 0.25;
    /** Ticks before a target at which a limited move creeps. */
    static final int CREEP_TICKS = 3;
    private final IntelligentInterfaceInputs inputs;
    private int previousDigital = -1;
    private boolean readEy;

    /**
     * @param config      the platform configuration (motor ports M1..M4; which input counts which wheel)
     * @param channel     the channel to the interface
     * @param inputs      where the latest inputs are published for the sensor platform
     */
    public IntelligentInterfaceMotorPlatform(PlatformConfig config, BrickChannel channel,
                                             IntelligentInterfaceInputs inputs) {
        super(config.robotName(), config.clock(), config.motorPorts());
        this.channel = channel;
        this.inputs = inputs;
        for (String port : config.motorPorts()) {
            FtMotors.index(port, IntelligentInterfaceTelegram.MOTORS);
        }
        this.ticksPerRevolution = config.wheels().stream().mapToInt(MotorChannel::encoderTicksPerRevolution).max().orElse(0);
        for (MotorChannel w : config.wheels()) {
            w.counter().ifPresent(c -> {
                int bit = IntelligentInterfaceTelegram.digitalInput(c);
                if (bit < 0) {
                    throw new IllegalArgumentException(config.source() + ": wheel counter '" + c
                            + "' must be a digital input of the Intelligent Interface, E1 to E8");
                }
                counterOf.put(w.port(), bit);
            });
        }
    }

    @Override
    public boolean hasEncoder(String port) {
        return counterOf.containsKey(port) && ticksPerRevolution > 0;
    }

    @Override
    protected void runImpl(List<MotorState> motors) {
        for (MotorState m : motors) {
            int i = FtMotors.index(m.port(), IntelligentInterfaceTelegram.MOTORS);
            duty[i] = FtMotors.duty(m.degreesPerSecond());
            limit[i] = m.running() ? m.limitDegrees() : Double.POSITIVE_INFINITY;
            ticksAtStart[i] = ticks[i];
        }
    }

    /**
     * The duty for this cycle: the wanted one, but at most {@link #CREEP_DUTY} within
     * {@link #CREEP_TICKS} ticks of a limited move's end. The interface keeps a motor on until the
     * next command, so the stop is as late as the link; creeping makes a late stop cost a quarter
     * as much.
     */
    private double cycleDuty(int i) {
        double d = Math.abs(duty[i]);
        if (ticksPerRevolution > 0 && Double.isFinite(limit[i]) && counted(i)) {
            double done = Math.abs(ticks[i] - ticksAtStart[i]) * 360.0 / ticksPerRevolution;
            if (limit[i] - done <= CREEP_TICKS * 360.0 / ticksPerRevolution) {
                d = Math.min(d, CREEP_DUTY);
            }
        }
        return d;
    }

    private boolean counted(int motor) {
        for (String port : counterOf.keySet()) {
            if (FtMotors.index(port, IntelligentInterfaceTelegram.MOTORS) == motor) {
                return true;
            }
        }
        return false;
    }

    @Override
    protected void pollFeedback() throws IOException {
        int motorByte = 0;
        for (int i = 0; i < duty.length; i++) {
            int direction = 0;
            if (duty[i] != 0) {
                accumulator[i] += cycleDuty(i);
                if (accumulator[i] >= 1) {
                    accumulator[i] -= 1;
                    direction = duty[i] > 0 ? IntelligentInterfaceTelegram.CW : IntelligentInterfaceTelegram.CCW;
                }
                lastDirection[i] = duty[i] > 0 ? 1 : -1;
            } else {
                accumulator[i] = 0;
            }
            motorByte = IntelligentInterfaceTelegram.withMotor(motorByte, i, direction);
        }
        int command = readEy ? ANALOG_EY : ANALOG_EX;
        readEy = !readEy;
        byte[] request = IntelligentInterfaceTelegram.request(command, motorByte);
        byte[] reply = channel.exchange((c, timeout) -> {
            c.send(request);
            return c.receiveExactly(3, timeout);
        });
        int digital = reply[0] & 0xFF;
        inputs.publish(digital, command == ANALOG_EX ? IntelligentInterfaceTelegram.analog(reply) : -1,
                command == ANALOG_EY ? IntelligentInterfaceTelegram.analog(reply) : -1);
        count(digital);
        enforceLimits();
    }

    /**
     * Stops a limited move on the link thread as soon as its count reaches the limit, as a brick
     * with a tacho limit does by itself: the execution action thread stops it too, a cycle later,
     * but a motor the interface keeps on until the next command must not wait for that thread.
     */
    private void enforceLimits() {
        if (ticksPerRevolution <= 0) {
            return;
        }
        for (int i = 0; i < duty.length; i++) {
            if (duty[i] != 0 && Double.isFinite(limit[i]) && counted(i)
                    && Math.abs(ticks[i] - ticksAtStart[i]) * 360.0 / ticksPerRevolution >= limit[i]) {
                duty[i] = 0;
                accumulator[i] = 0;
                limit[i] = Double.POSITIVE_INFINITY;
            }
        }
    }

    /** Counts impulse-wheel transitions and reports the wheels' rotation. */
    private void count(int digital) {
        for (Map.Entry<String, Integer> e : counterOf.entrySet()) {
            int motor = FtMotors.index(e.getKey(), IntelligentInterfaceTelegram.MOTORS);
            int bit = 1 << e.getValue();
            if (previousDigital >= 0 && ((digital ^ previousDigital) & bit) != 0) {
                ticks[motor] += lastDirection[motor] >= 0 ? 1 : -1;
            }
            if (ticksPerRevolution > 0) {
                reportDegrees(e.getKey(), ticks[motor] * 360.0 / ticksPerRevolution);
            }
        }
        previousDigital = digital;
    }
}
