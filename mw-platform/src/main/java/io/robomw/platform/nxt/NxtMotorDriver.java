package io.robomw.platform.nxt;

import io.robomw.api.Clock;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorState;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.ArrayList;
import java.util.List;

/**
 * The NXT's motor driver: motor states become SETOUTPUTSTATE telegrams (regulated speed, the
 * rotation as the brick's tacho limit, brake when stopping, coast when closing; two motors started
 * together at the same speed for the same rotation run synchronised, so the robot drives
 * straight), and the encoders are read with GETOUTPUTSTATE's rotation count.
 *
 * <h2>Tacho limits as the firmware counts them</h2>
 * The firmware adds each new tacho limit to the motor's running target and zeroes that target
 * only on UPDATE_RESET_COUNT ({@code d_output.c dOutputSetTachoLimit}); a rotation pre-empted
 * before its end would leave its remainder in the target, and the next rotation would end in the
 * wrong place. So every limited rotation goes out as UPDATE_RESET_COUNT, then SETOUTPUTSTATE: it
 * ends exactly its limit from where the motor is when the brick takes it. A synchronised pair also
 * gets its block tacho counts reset first (RESETMOTORPOSITION relative), since the firmware keeps
 * the pair in step by their difference. A limited rotation is over when the brick reports the
 * output's run state idle ({@link FeedbackSink#stoppedAtLimit}: the link side brakes it at once).
 * Firmware older than 1.29 has no UPDATE_RESET_COUNT (it answers 0xBE when the robot opens): then
 * no tacho limit is sent and the link side stops each rotation by the encoder, just in time, like a
 * brick without limits.
 *
 * <h2>Over a slow link</h2>
 * Each cycle's telegrams go out {@link NxtBrick#pipeline pipelined}: the motor changes (resets and
 * SETOUTPUTSTATEs, so motors started together start within a millisecond of each other) and the
 * GETOUTPUTSTATE polls in one write, their replies read afterwards; one round trip per cycle,
 * whatever the number of motors. Only motors that matter are polled every cycle: those running,
 * and those stopped less than {@link #SETTLE_NANOS} ago (their coasting still shows in the
 * encoder); the others once every {@link #IDLE_POLL_NANOS}. A keep-alive goes out every minute.
 */
public final class NxtMotorDriver implements MotorDriver, LinkTiming {

    private static final Logger LOG = LoggerFactory.getLogger(NxtMotorDriver.class);

    private static final long KEEP_ALIVE_NANOS = 60_000_000_000L;
    /** How long a stopped motor is still polled every cycle. */
    static final long SETTLE_NANOS = 300_000_000L;
    /** How often a motor at rest is polled. */
    static final long IDLE_POLL_NANOS = 1_000_000_000L;

    private final NxtBrick brick;
    private final Clock clock;
    /** The motor ports, in the description's order, and each one's NXT output number. */
    private final List<String> ports;
    private final int[] outputs;
    // By port index; link side only:
    private final MotorState[] commanded;
    private final long[] changedAt;
    private final long[] polledAt;
    private volatile boolean resetCountCommand = true;
    private boolean polledThisCycle;
    private long lastKeepAlive;

    /**
     * @param config the platform configuration (motor ports A, B, C)
     * @param brick  the brick
     * @throws IllegalArgumentException if a motor port is not A, B or C
     */
    public NxtMotorDriver(PlatformConfig config, NxtBrick brick) {
        this.brick = brick;
        this.clock = config.clock();
        this.ports = List.copyOf(config.motorPorts());
        this.outputs = new int[ports.size()];
        for (int i = 0; i < outputs.length; i++) {
            outputs[i] = outputPort(ports.get(i));
        }
        this.commanded = new MotorState[ports.size()];
        this.changedAt = new long[ports.size()];
        this.polledAt = new long[ports.size()];
        java.util.Arrays.fill(polledAt, Long.MIN_VALUE);
        this.lastKeepAlive = clock.nanoTime();
    }

    /**
     * @param port a motor port name
     * @return its NXT output number: A = 0, B = 1, C = 2
     * @throws IllegalArgumentException if the NXT has no such output
     */
    static int outputPort(String port) {
        return switch (port) {
            case "A" -> 0;
            case "B" -> 1;
            case "C" -> 2;
            default -> throw new IllegalArgumentException("the NXT has motor ports A, B and C, not '" + port + "'");
        };
    }

    /**
     * @param degreesPerSecond a motor speed
     * @return the NXT power that regulates to it, -100..100
     */
    static int power(double degreesPerSecond) {
        long p = Math.round(degreesPerSecond / NxtTelegram.DEGREES_PER_SECOND_AT_FULL_POWER * 100);
        return (int) Math.max(-100, Math.min(100, p));
    }

    @Override
    public LinkTiming timing() {
        return this;
    }

    /**
     * With UPDATE_RESET_COUNT, the NXT ends a rotation at its tacho limit itself and then reports
     * the output idle; without it, the link side stops rotations by the encoder.
     */
    @Override
    public boolean stopsAtLimit() {
        return resetCountCommand;
    }

    /** Half the measured round trip of the brick's link. */
    @Override
    public long oneWayDelayNanos() {
        return brick.roundTrip().oneWayNanos();
    }

    /** The exchange under way on the channel (a poll, a sensor read): a command waits for it. */
    @Override
    public long nanosUntilFree() {
        return brick.nanosUntilFree();
    }

    /** Without tacho limits (firmware before 1.29), the link side stops rotations just in time itself. */
    @Override
    public boolean stopsOnLinkSide() {
        return !resetCountCommand;
    }

    /** The next telegram can go after this cycle's pipelined exchange, at the earliest a cycle from now. */
    @Override
    public long nextSendNanos(long cycleNanos) {
        return Math.max(cycleNanos, brick.roundTrip().nanos());
    }

    @Override
    public void send(List<MotorState> motors, FeedbackSink feedback) throws IOException {
        boolean sync = motors.size() == 2 && motors.get(0).running() && motors.get(1).running()
                && motors.get(0).degreesPerSecond() == motors.get(1).degreesPerSecond()
                && motors.get(0).limitDegrees() == motors.get(1).limitDegrees();
        List<NxtBrick.Request> batch = new ArrayList<>();
        for (MotorState m : motors) {
            int port = outputPort(m.port());
            if (m.running() && limited(m)) {
                batch.add(new NxtBrick.Request(NxtTelegram.updateResetCount(true, port), NxtTelegram.STATUS_REPLY, port));
            }
            if (sync) {
                batch.add(new NxtBrick.Request(NxtTelegram.resetMotorPosition(true, port, true), NxtTelegram.STATUS_REPLY, port));
            }
        }
        for (MotorState m : motors) {
            int port = outputPort(m.port());
            batch.add(new NxtBrick.Request(NxtTelegram.setOutputState(true, outputState(m, port, sync)), NxtTelegram.STATUS_REPLY, port));
        }
        int motorTelegrams = batch.size();
        long now = clock.nanoTime();
        for (MotorState m : motors) {
            int i = ports.indexOf(m.port());
            commanded[i] = m;
            changedAt[i] = now;
        }
        List<Integer> polled = toPoll(now);
        for (int i : polled) {
            batch.add(new NxtBrick.Request(NxtTelegram.getOutputState(outputs[i]), NxtTelegram.GETOUTPUTSTATE_REPLY, outputs[i]));
        }
        List<byte[]> replies = brick.pipeline(batch);
        readPolls(polled, replies.subList(motorTelegrams, replies.size()), batch.subList(motorTelegrams, batch.size()), feedback);
        polledThisCycle = true;
        brick.checkStatus(batch.subList(0, motorTelegrams), replies.subList(0, motorTelegrams));
    }

    private boolean limited(MotorState m) {
        return resetCountCommand && !Double.isInfinite(m.limitDegrees());
    }

    /** @return the output state a motor state is on the NXT */
    OutputState outputState(MotorState m, int port, boolean sync) {
        if (m.running()) {
            long limit = limited(m) ? Math.max(1, Math.round(m.limitDegrees())) : 0;
            return OutputState.running(port, power(m.degreesPerSecond()), sync ? OutputState.Regulation.SYNC : OutputState.Regulation.SPEED, limit);
        }
        return m.stopMode() == MotorState.StopMode.BRAKE ? OutputState.braked(port) : OutputState.coasting(port);
    }

    /**
     * Polls the motors that matter (unless this cycle's telegrams carried the polls) and keeps the
     * brick awake.
     *
     * @return the motors polled that run or settle
     */
    @Override
    public int poll(FeedbackSink feedback) throws IOException {
        long now = clock.nanoTime();
        if (!polledThisCycle) {
            List<Integer> polled = toPoll(now);
            if (!polled.isEmpty()) {
                List<NxtBrick.Request> requests = new ArrayList<>();
                for (int i : polled) {
                    requests.add(new NxtBrick.Request(NxtTelegram.getOutputState(outputs[i]), NxtTelegram.GETOUTPUTSTATE_REPLY, outputs[i]));
                }
                readPolls(polled, brick.pipeline(requests), requests, feedback);
            }
        }
        polledThisCycle = false;
        if (now - lastKeepAlive > KEEP_ALIVE_NANOS) {
            lastKeepAlive = now;
            brick.keepAlive();
        }
        int moving = 0;
        for (int i = 0; i < ports.size(); i++) {
            if (moving(i, now)) {
                moving++;
            }
        }
        return moving;
    }

    /** @return whether a motor runs, or stopped less than {@link #SETTLE_NANOS} ago (its coasting still shows in the encoder) */
    private boolean moving(int i, long now) {
        MotorState m = commanded[i];
        return m != null && (m.running() || now - changedAt[i] < SETTLE_NANOS);
    }

    /** The motors to poll now, by index: moving, or not polled for {@link #IDLE_POLL_NANOS}. */
    private List<Integer> toPoll(long now) {
        List<Integer> out = new ArrayList<>(ports.size());
        for (int i = 0; i < ports.size(); i++) {
            if (moving(i, now) || polledAt[i] == Long.MIN_VALUE || now - polledAt[i] >= IDLE_POLL_NANOS) {
                out.add(i);
            }
        }
        return out;
    }

    private void readPolls(List<Integer> polled, List<byte[]> replies, List<NxtBrick.Request> requests, FeedbackSink feedback) throws IOException {
        long now = clock.nanoTime();
        for (int k = 0; k < polled.size(); k++) {
            byte[] reply = replies.get(k);
            brick.checkStatus(requests.get(k), reply);
            NxtTelegram.OutputReading reading = brick.outputReading(reply);
            int i = polled.get(k);
            polledAt[i] = now;
            feedback.degrees(i, reading.rotationCount());
            if (reading.state().runState() == OutputState.RunState.IDLE) {
                feedback.stoppedAtLimit(ports.get(i));
            }
        }
    }

    /**
     * Zeroes every motor's rotation count, so encoders count from the platform's start, and its
     * tacho count and target; learns whether the firmware has UPDATE_RESET_COUNT.
     *
     * @throws IOException if the link failed
     */
    void resetCounters() throws IOException {
        List<NxtBrick.Request> requests = new ArrayList<>();
        for (int p : outputs) {
            requests.add(new NxtBrick.Request(NxtTelegram.resetMotorPosition(true, p, false), NxtTelegram.STATUS_REPLY, p));
            requests.add(new NxtBrick.Request(NxtTelegram.updateResetCount(true, p), NxtTelegram.STATUS_REPLY, p));
        }
        List<byte[]> replies = brick.pipeline(requests);
        for (int i = 0; i < replies.size(); i++) {
            boolean resetCount = NxtTelegram.opcode(requests.get(i).telegram()) == NxtTelegram.UPDATE_RESET_COUNT;
            if (resetCount && NxtTelegram.status(replies.get(i)) == NxtStatus.UNKNOWN_COMMAND) {
                if (resetCountCommand) {
                    LOG.info("robot '{}': the NXT's firmware has no UPDATE_RESET_COUNT (older than 1.29); rotations are stopped by the "
                            + "encoder instead of the brick's tacho limit", brick.robot());
                }
                resetCountCommand = false;
            } else {
                brick.checkStatus(requests.get(i), replies.get(i));
            }
        }
    }
}
