package io.robomw.platform.nxt;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.motor.MotorState;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;

/**
 * The NXT's motor platform: motor states become SETOUTPUTSTATE telegrams (regulated speed, the
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
 * output's run state idle. Firmware older than 1.29 has no UPDATE_RESET_COUNT (it answers 0xBE
 * when the robot opens): then no tacho limit is sent and the platform stops each rotation by the
 * encoder, like a brick without limits.
 *
 * <h2>Over a slow link</h2>
 * Each cycle's telegrams go out {@link NxtBrick#pipeline pipelined}: the motor changes (resets and
 * SETOUTPUTSTATEs, so motors started together start within a millisecond of each other) and the
 * GETOUTPUTSTATE polls in one write, their replies read afterwards; one round trip per cycle,
 * whatever the number of motors. Only motors that matter are polled every cycle: those running,
 * and those stopped less than {@link #SETTLE_NANOS} ago (their coasting still shows in the
 * encoder); the others once every {@link #IDLE_POLL_NANOS}. A keep-alive goes out every minute.
 */
public final class NxtMotorPlatform extends GenericMotorPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(NxtMotorPlatform.class);

    private static final long KEEP_ALIVE_NANOS = 60_000_000_000L;
    /** How long a stopped motor is still polled every cycle. */
    static final long SETTLE_NANOS = 300_000_000L;
    /** How often a motor at rest is polled. */
    static final long IDLE_POLL_NANOS = 1_000_000_000L;

    private final NxtBrick brick;
    private final Map<String, MotorState> commanded = new HashMap<>();
    private final Map<String, Long> changedAt = new HashMap<>();
    private final Map<String, Long> polledAt = new HashMap<>();
    private boolean resetCountCommand = true;
    private boolean polledThisCycle;
    private long lastKeepAlive;

    /**
     * @param config the platform configuration (motor ports A, B, C)
     * @param brick  the brick
     */
    public NxtMotorPlatform(PlatformConfig config, NxtBrick brick) {
        super(config.robotName(), config.clock(), config.motorPorts());
        this.brick = brick;
        for (String port : config.motorPorts()) {
            outputPort(port);
        }
        this.lastKeepAlive = clock().nanoTime();
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

    /**
     * With UPDATE_RESET_COUNT, the NXT ends a rotation at its tacho limit itself and then reports
     * the output idle; without it, the platform stops rotations by the encoder.
     */
    @Override
    protected boolean stopsAtLimit() {
        return resetCountCommand;
    }

    /** Half the measured round trip of the brick's link. */
    @Override
    protected long linkDelayNanos() {
        return brick.roundTrip().oneWayNanos();
    }

    /** The link's one-way delay, after the exchange under way (a poll, a sensor read) ends. */
    @Override
    protected long commandDelayNanos() {
        return brick.nanosUntilFree() + linkDelayNanos();
    }

    /** Without tacho limits (firmware before 1.29), the link thread stops rotations just in time itself. */
    @Override
    protected boolean stopsOnLinkSide() {
        return !resetCountCommand;
    }

    /** The next telegram can go after this cycle's pipelined exchange, at the earliest a cycle from now. */
    @Override
    protected long nextSendNanos() {
        return Math.max(super.nextSendNanos(), brick.roundTrip().nanos());
    }

    @Override
    protected void runImpl(List<MotorState> motors) throws IOException {
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
            batch.add(new NxtBrick.Request(setOutputState(m, port, sync), NxtTelegram.STATUS_REPLY, port));
        }
        int motorTelegrams = batch.size();
        long now = clock().nanoTime();
        for (MotorState m : motors) {
            commanded.put(m.port(), m);
            changedAt.put(m.port(), now);
        }
        List<String> polled = toPoll(now);
        for (String port : polled) {
            int p = outputPort(port);
            batch.add(new NxtBrick.Request(NxtTelegram.getOutputState(p), NxtTelegram.GETOUTPUTSTATE_REPLY, p));
        }
        List<byte[]> replies = brick.pipeline(batch);
        readPolls(polled, replies.subList(motorTelegrams, replies.size()), batch.subList(motorTelegrams, batch.size()));
        polledThisCycle = true;
        for (int i = 0; i < motorTelegrams; i++) {
            int status = replies.get(i)[NxtTelegram.STATUS_OFFSET] & 0xFF;
            if (status != NxtStatus.SUCCESS) {
                throw new NxtException(brick.robot(), batch.get(i).telegram()[1] & 0xFF, batch.get(i).port(), status, batch.get(i).telegram());
            }
        }
    }

    private boolean limited(MotorState m) {
        return resetCountCommand && !Double.isInfinite(m.limitDegrees());
    }

    private byte[] setOutputState(MotorState m, int port, boolean sync) {
        if (m.running()) {
            long limit = limited(m) ? Math.max(1, Math.round(m.limitDegrees())) : 0;
            return NxtTelegram.setOutputState(true, port, power(m.degreesPerSecond()),
                    NxtTelegram.MODE_MOTORON | NxtTelegram.MODE_BRAKE | NxtTelegram.MODE_REGULATED,
                    sync ? NxtTelegram.REGULATION_SYNC : NxtTelegram.REGULATION_SPEED, 0, NxtTelegram.RUN_RUNNING, limit);
        }
        if (m.stopMode() == MotorState.StopMode.BRAKE) {
            return NxtTelegram.setOutputState(true, port, 0, NxtTelegram.MODE_MOTORON | NxtTelegram.MODE_BRAKE | NxtTelegram.MODE_REGULATED,
                    NxtTelegram.REGULATION_SPEED, 0, NxtTelegram.RUN_RUNNING, 0);
        }
        return NxtTelegram.setOutputState(true, port, 0, 0, NxtTelegram.REGULATION_IDLE, 0, NxtTelegram.RUN_IDLE, 0);
    }

    @Override
    protected void pollFeedback() throws IOException {
        long now = clock().nanoTime();
        if (!polledThisCycle) {
            List<String> polled = toPoll(now);
            if (!polled.isEmpty()) {
                List<NxtBrick.Request> requests = new ArrayList<>();
                for (String port : polled) {
                    int p = outputPort(port);
                    requests.add(new NxtBrick.Request(NxtTelegram.getOutputState(p), NxtTelegram.GETOUTPUTSTATE_REPLY, p));
                }
                readPolls(polled, brick.pipeline(requests), requests);
            }
        }
        polledThisCycle = false;
        if (now - lastKeepAlive > KEEP_ALIVE_NANOS) {
            lastKeepAlive = now;
            brick.keepAlive();
        }
    }

    /** The motors to poll now: running, stopped within {@link #SETTLE_NANOS}, or not polled for {@link #IDLE_POLL_NANOS}. */
    private List<String> toPoll(long now) {
        Set<String> out = new LinkedHashSet<>();
        for (String port : ports()) {
            MotorState m = commanded.get(port);
            Long changed = changedAt.get(port);
            Long polled = polledAt.get(port);
            if ((m != null && m.running()) || (changed != null && now - changed < SETTLE_NANOS)
                    || polled == null || now - polled >= IDLE_POLL_NANOS) {
                out.add(port);
            }
        }
        return new ArrayList<>(out);
    }

    private void readPolls(List<String> ports, List<byte[]> replies, List<NxtBrick.Request> requests) {
        long now = clock().nanoTime();
        for (int i = 0; i < ports.size(); i++) {
            byte[] reply = replies.get(i);
            int status = reply[NxtTelegram.STATUS_OFFSET] & 0xFF;
            if (status != NxtStatus.SUCCESS) {
                throw new NxtException(brick.robot(), NxtTelegram.GETOUTPUTSTATE, requests.get(i).port(), status, requests.get(i).telegram());
            }
            String port = ports.get(i);
            polledAt.put(port, now);
            reportDegrees(port, LittleEndian.s32(reply, ROTATION_COUNT_OFFSET));
            if (reply[RUN_STATE_OFFSET] == NxtTelegram.RUN_IDLE) {
                reportStoppedAtLimit(port);
            }
        }
    }

    /** Offset of the run state in a GETOUTPUTSTATE reply. */
    private static final int RUN_STATE_OFFSET = 8;
    /** Offset of the rotation count in a GETOUTPUTSTATE reply. */
    private static final int ROTATION_COUNT_OFFSET = 21;

    /**
     * Zeroes every motor's rotation count, so encoders count from the platform's start, and its
     * tacho count and target; learns whether the firmware has UPDATE_RESET_COUNT.
     *
     * @throws IOException if the link failed
     */
    void resetCounters() throws IOException {
        List<NxtBrick.Request> requests = new ArrayList<>();
        for (String port : ports()) {
            int p = outputPort(port);
            requests.add(new NxtBrick.Request(NxtTelegram.resetMotorPosition(true, p, false), NxtTelegram.STATUS_REPLY, p));
            requests.add(new NxtBrick.Request(NxtTelegram.updateResetCount(true, p), NxtTelegram.STATUS_REPLY, p));
        }
        List<byte[]> replies = brick.pipeline(requests);
        for (int i = 0; i < replies.size(); i++) {
            int status = replies.get(i)[NxtTelegram.STATUS_OFFSET] & 0xFF;
            boolean resetCount = (requests.get(i).telegram()[1] & 0xFF) == NxtTelegram.UPDATE_RESET_COUNT;
            if (resetCount && status == NxtStatus.UNKNOWN_COMMAND) {
                if (resetCountCommand) {
                    LOG.info("robot '{}': the NXT's firmware has no UPDATE_RESET_COUNT (older than 1.29); rotations are stopped by the "
                            + "encoder instead of the brick's tacho limit", brick.robot());
                }
                resetCountCommand = false;
            } else if (status != NxtStatus.SUCCESS) {
                throw new NxtException(brick.robot(), requests.get(i).telegram()[1] & 0xFF, requests.get(i).port(), status, requests.get(i).telegram());
            }
        }
    }
}
