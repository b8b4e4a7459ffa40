package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.List;

/**
 * The NXT's motor platform: motor states become SETOUTPUTSTATE telegrams (regulated speed, the
 * remaining rotation as the brick's tacho limit, brake when stopping; two motors started together
 * at the same speed for the same rotation run synchronised, so the robot drives straight), and the
 * encoders are read with GETOUTPUTSTATE's rotation count. A limited rotation is over when the
 * brick reports the output's run state idle (it stopped at the tacho limit, counted from where the
 * motor was when the telegram arrived). A keep-alive goes out every minute.
 */
public final class NxtMotorPlatform extends GenericMotorPlatform {

    private static final long KEEP_ALIVE_NANOS = 60_000_000_000L;

    private final NxtBrick brick;
    /** When the last keep-alive went, on the platform's clock (set at the first service). */
    private long lastKeepAlive = Long.MIN_VALUE;

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

    /** The NXT ends a rotation at its tacho limit itself and then reports the output idle. */
    @Override
    protected boolean stopsAtLimit() {
        return true;
    }

    @Override
    protected void runImpl(List<MotorState> motors) throws IOException {
        boolean sync = motors.size() == 2 && motors.get(0).running() && motors.get(1).running()
                && motors.get(0).degreesPerSecond() == motors.get(1).degreesPerSecond()
                && motors.get(0).limitDegrees() == motors.get(1).limitDegrees();
        java.util.List<byte[]> telegrams = new java.util.ArrayList<>();
        int[] ports = new int[motors.size()];
        for (MotorState m : motors) {
            int port = outputPort(m.port());
            ports[telegrams.size()] = port;
            byte[] telegram;
            if (m.running()) {
                long limit = Double.isInfinite(m.limitDegrees()) ? 0 : Math.max(1, Math.round(m.limitDegrees()));
                telegram = NxtTelegram.setOutputState(true, port, power(m.degreesPerSecond()),
                        NxtTelegram.MODE_MOTORON | NxtTelegram.MODE_BRAKE | NxtTelegram.MODE_REGULATED,
                        sync ? NxtTelegram.REGULATION_SYNC : NxtTelegram.REGULATION_SPEED, 0, NxtTelegram.RUN_RUNNING, limit);
            } else if (m.stopMode() == MotorState.StopMode.BRAKE) {
                telegram = NxtTelegram.setOutputState(true, port, 0, NxtTelegram.MODE_MOTORON | NxtTelegram.MODE_BRAKE | NxtTelegram.MODE_REGULATED,
                        NxtTelegram.REGULATION_SPEED, 0, NxtTelegram.RUN_RUNNING, 0);
            } else {
                telegram = NxtTelegram.setOutputState(true, port, 0, 0, NxtTelegram.REGULATION_IDLE, 0, NxtTelegram.RUN_IDLE, 0);
            }
            telegrams.add(telegram);
        }
        brick.requestAll(telegrams, ports);
    }

    @Override
    protected void pollFeedback() throws IOException {
        for (String port : ports()) {
            int p = outputPort(port);
            byte[] reply = brick.request(NxtTelegram.getOutputState(p), NxtTelegram.GETOUTPUTSTATE_REPLY, p);
            reportDegrees(port, LittleEndian.s32(reply, 21));
            if (reply[8] == NxtTelegram.RUN_IDLE) {
                reportStoppedAtLimit(port);
            }
        }
        long now = clock().nanoTime();
        if (lastKeepAlive == Long.MIN_VALUE) {
            lastKeepAlive = now;
        } else if (now - lastKeepAlive > KEEP_ALIVE_NANOS) {
            lastKeepAlive = now;
            brick.keepAlive();
        }
    }

    /**
     * Zeroes every motor's rotation count, so encoders count from the platform's start.
     *
     * @throws IOException if the link failed
     */
    void resetCounters() throws IOException {
        for (String port : ports()) {
            int p = outputPort(port);
            brick.request(NxtTelegram.resetMotorPosition(true, p, false), NxtTelegram.STATUS_REPLY, p);
        }
    }
}
