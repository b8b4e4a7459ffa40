package io.robomw.platform.rcx;

import io.robomw.api.Clock;
import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * The RCX's motor driver. The RCX sets a motor's power in eight steps (0..7, no speed
 * regulation), its direction, and switches it on, off (braking) or to float; it has no encoders:
 * a wheel's rotation is counted by a rotation sensor on an input (the wheel's {@code counter:},
 * {@code S1}..{@code S3}), 16 counts per turn of its axle ({@code encoder_ticks_per_revolution}).
 *
 * <h2>What goes over the link</h2>
 * A batch of motor states becomes Set motor power (once per power step the batch needs, all the
 * motors at that step in one packet), Set motor direction (likewise), then one Set motor on/off
 * per state, all motors in it at once: motors started together start in the same packet. Power
 * and direction are sent only when they change. Every packet is a round trip through the tower
 * at 2400 baud (about 0.12 s), so the wheels' rotation sensors are read only while a wheel turns
 * or has just stopped, and the link thread stops a rotation itself, just in time by its
 * prediction, rather than waiting for the execution action thread.
 *
 * <h2>Speed</h2>
 * Power step p turns a motor at (p + 1) / 8 of {@link #DEGREES_PER_SECOND_AT_FULL_POWER}: the
 * driver takes the step nearest the wanted speed, and predicts with the step's speed. The
 * constant is shared with the emulator.
 */
public final class RcxMotorDriver implements MotorDriver, LinkTiming {

    /**
     * Speed of a motor at power 7, degrees per second of the shaft the description counts (a 9 V
     * Technic motor geared down to a wheel, as RCX robots are built): 600.
     */
    public static final double DEGREES_PER_SECOND_AT_FULL_POWER = 600;
    /** Power steps. */
    public static final int POWER_STEPS = 8;
    /** How long a stopped wheel's rotation sensor is still read every cycle. */
    static final long SETTLE_NANOS = 400_000_000L;

    private final RcxBrick brick;
    private final Clock clock;
    private final List<String> ports;
    private final Map<String, Integer> counterOf = new HashMap<>();
    private final int ticksPerRevolution;
    private final Map<String, Integer> power = new HashMap<>();
    private final Map<String, Integer> direction = new HashMap<>();
    private final Map<String, MotorState> running = new HashMap<>();
    private final Map<String, Long> changedAt = new HashMap<>();
    private final Map<String, Long> polledAt = new HashMap<>();

    /**
     * @param config the platform configuration (motor ports A, B, C; wheels counted by rotation sensors on S1..S3)
     * @param brick  the brick
     */
    public RcxMotorDriver(PlatformConfig config, RcxBrick brick) {
        this.brick = brick;
        this.clock = config.clock();
        this.ports = List.copyOf(config.motorPorts());
        for (String port : config.motorPorts()) {
            motorBit(port);
        }
        this.ticksPerRevolution = config.wheels().stream().mapToInt(MotorChannel::encoderTicksPerRevolution).max().orElse(0);
        for (MotorChannel w : config.wheels()) {
            w.counter().ifPresent(c -> counterOf.put(w.port(), RcxSensorPlatform.inputIndex(c, config.source())));
        }
    }

    /**
     * @param port a motor port name
     * @return its motor bit: A = 1, B = 2, C = 4
     * @throws IllegalArgumentException if the RCX has no such output
     */
    static int motorBit(String port) {
        return switch (port) {
            case "A" -> RcxPacket.MOTOR_A;
            case "B" -> RcxPacket.MOTOR_B;
            case "C" -> RcxPacket.MOTOR_C;
            default -> throw new IllegalArgumentException("the RCX has motor ports A, B and C, not '" + port + "'");
        };
    }

    /**
     * @param degreesPerSecond a wanted speed, not 0
     * @return the power step whose speed is nearest to it, 0..7
     */
    public static int powerStep(double degreesPerSecond) {
        long step = Math.round(Math.abs(degreesPerSecond) / DEGREES_PER_SECOND_AT_FULL_POWER * POWER_STEPS) - 1;
        return (int) Math.max(0, Math.min(POWER_STEPS - 1, step));
    }

    /**
     * @param step a power step 0..7
     * @return the speed the motor turns at, degrees per second
     */
    public static double speedAt(int step) {
        return (step + 1) * DEGREES_PER_SECOND_AT_FULL_POWER / POWER_STEPS;
    }

    @Override
    public boolean hasEncoder(String port) {
        return counterOf.containsKey(port) && ticksPerRevolution > 0;
    }

    @Override
    public LinkTiming timing() {
        return this;
    }

    /** A rotation sensor's count is 22.5° of its axle (16 a turn). */
    @Override
    public double encoderResolutionDegrees(String port) {
        return hasEncoder(port) ? 360.0 / ticksPerRevolution : 0;
    }

    /** The RCX turns a motor at its power step's speed, not the one asked for. */
    @Override
    public double actualDegreesPerSecond(MotorState state) {
        return state.running() ? Math.signum(state.degreesPerSecond()) * speedAt(powerStep(state.degreesPerSecond())) : 0;
    }

    /** The link side stops rotations itself, just in time: a stop from the action thread could wait a whole exchange. */
    @Override
    public boolean stopsOnLinkSide() {
        return true;
    }

    /**
     * How old a rotation sensor's reading is when it arrives: the brick reads the sensor when a Get
     * value packet (11 bytes) has arrived, and its echo and reply (22 bytes) follow: two thirds of
     * the measured round trip.
     */
    @Override
    public long oneWayDelayNanos() {
        return brick.roundTrip().nanos() * 2 / 3;
    }

    /** The last packet of a batch acted when it had arrived: its echo and reply (16 of 25 bytes) came after. */
    @Override
    public long actedNanosAgo() {
        return brick.roundTrip().nanos() * 16 / 25;
    }

    /**
     * How long a stop takes to act: a Set motor on/off packet (9 bytes) is about a third of its
     * round trip with echo and reply (25 bytes); after the exchange under way.
     */
    @Override
    public long commandDelayNanos() {
        return brick.nanosUntilFree() + brick.roundTrip().nanos() * 9 / 25;
    }

    /** The next packet can go after this cycle's exchanges: a round trip for each wheel read. */
    @Override
    public long nextSendNanos(long cycleNanos) {
        return Math.max(cycleNanos, brick.roundTrip().nanos() * Math.max(1, counterOf.size()));
    }

    @Override
    public void send(List<MotorState> motors, FeedbackSink feedback) throws IOException {
        long now = clock.nanoTime();
        Map<Integer, Integer> byPower = new LinkedHashMap<>();
        Map<Integer, Integer> byDirection = new LinkedHashMap<>();
        Map<Integer, Integer> byState = new LinkedHashMap<>();
        for (MotorState m : motors) {
            int bit = motorBit(m.port());
            changedAt.put(m.port(), now);
            running.put(m.port(), m);
            if (!m.running()) {
                byState.merge(m.stopMode() == MotorState.StopMode.BRAKE ? RcxPacket.OFF : RcxPacket.FLOAT, bit, (a, b) -> a | b);
                continue;
            }
            int step = powerStep(m.degreesPerSecond());
            if (!Integer.valueOf(step).equals(power.get(m.port()))) {
                byPower.merge(step, bit, (a, b) -> a | b);
            }
            int dir = m.degreesPerSecond() > 0 ? RcxPacket.FORWARD : RcxPacket.REVERSE;
            if (!Integer.valueOf(dir).equals(direction.get(m.port()))) {
                byDirection.merge(dir, bit, (a, b) -> a | b);
            }
            byState.merge(RcxPacket.ON, bit, (a, b) -> a | b);
        }
        for (Map.Entry<Integer, Integer> e : byPower.entrySet()) {
            brick.request(RcxPacket.SET_MOTOR_POWER, RcxPacket.setMotorPower(e.getValue(), e.getKey()));
            remember(power, e.getValue(), e.getKey());
        }
        for (Map.Entry<Integer, Integer> e : byDirection.entrySet()) {
            brick.request(RcxPacket.SET_MOTOR_DIRECTION, RcxPacket.setMotorDirection(e.getValue(), e.getKey()));
            remember(direction, e.getValue(), e.getKey());
        }
        for (Map.Entry<Integer, Integer> e : byState.entrySet()) {
            brick.request(RcxPacket.SET_MOTOR_ON_OFF, RcxPacket.setMotorOnOff(e.getValue(), e.getKey()));
        }
    }

    private void remember(Map<String, Integer> values, int motors, int value) {
        for (String port : ports) {
            if ((motors & motorBit(port)) != 0) {
                values.put(port, value);
            }
        }
    }

    /**
     * Reads the rotation sensor of every wheel that turns, or stopped less than
     * {@link #SETTLE_NANOS} ago, or was not read for a second.
     *
     * @return the wheels read that turn or settle
     */
    @Override
    public int poll(FeedbackSink feedback) throws IOException {
        long now = clock.nanoTime();
        int moving = 0;
        for (Map.Entry<String, Integer> e : counterOf.entrySet()) {
            String port = e.getKey();
            MotorState m = running.get(port);
            Long changed = changedAt.get(port);
            Long polled = polledAt.get(port);
            boolean settling = (m != null && m.running()) || (changed != null && now - changed < SETTLE_NANOS);
            boolean due = settling || polled == null || now - polled >= 1_000_000_000L;
            if (!due || ticksPerRevolution <= 0) {
                continue;
            }
            int counts = brick.request(RcxPacket.GET_VALUE, RcxPacket.getValue(RcxPacket.SOURCE_SENSOR_VALUE, e.getValue())).s16();
            polledAt.put(port, clock.nanoTime());
            feedback.degrees(port, counts * 360.0 / ticksPerRevolution);
            if (settling) {
                moving++;
            }
        }
        return moving;
    }

    /**
     * Sets up every wheel's rotation sensor (type rotation, mode angle), which zeroes its count,
     * and floats every motor.
     *
     * @throws IOException if the brick does not answer
     */
    void setUp() throws IOException {
        for (int input : counterOf.values()) {
            brick.request(RcxPacket.SET_SENSOR_TYPE, RcxPacket.setSensorType(input, RcxPacket.TYPE_ROTATION));
            brick.request(RcxPacket.SET_SENSOR_MODE, RcxPacket.setSensorMode(input, RcxPacket.MODE_ANGLE));
        }
        int all = 0;
        for (String port : ports) {
            all |= motorBit(port);
        }
        if (all != 0) {
            brick.request(RcxPacket.SET_MOTOR_ON_OFF, RcxPacket.setMotorOnOff(all, RcxPacket.FLOAT));
        }
    }
}
