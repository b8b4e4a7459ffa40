package io.robomw.examples.driver;

import io.robomw.api.Clock;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorState;

import java.io.IOException;
import java.util.List;

/**
 * The LineBot's motor driver: a motor state becomes {@code SPEED m dps} or {@code STOP m BRAKE|COAST};
 * a poll is {@code COUNT}, whose two numbers are the encoders. The board has no rotation limit of
 * its own, so the motor platform stops each rotation by the encoder, with the link's delay taken
 * into account ({@link #oneWayDelayNanos()}: half the round trip the board measures, and the
 * exchange under way, {@link #nanosUntilFree()}). Polls also keep the board's watchdog fed: the
 * link agent comes round every cycle while a motor moves and ten times a second while none does,
 * well within the board's {@value LineBotProtocol#WATCHDOG_MILLIS} ms.
 *
 * <p>{@link #send} and {@link #poll} run on the link side only (the link agent's thread).
 */
public final class LineBotMotorDriver implements MotorDriver, LinkTiming {

    /** How long a stopped motor still counts as moving (it may still be coasting). */
    static final long SETTLE_NANOS = 300_000_000L;

    private final LineBot bot;
    private final Clock clock;
    private final List<String> ports;
    // By port index; link side only: each motor's last state, and when it was sent.
    private final MotorState[] commanded;
    private final long[] changedAt;

    /**
     * @param config the platform configuration (motor ports A and B)
     * @param bot    the board
     * @throws IllegalArgumentException if a motor port is not A or B
     */
    public LineBotMotorDriver(PlatformConfig config, LineBot bot) {
        this.bot = bot;
        this.clock = config.clock();
        this.ports = List.copyOf(config.motorPorts());
        ports.forEach(LineBotProtocol::motor);
        this.commanded = new MotorState[ports.size()];
        this.changedAt = new long[ports.size()];
    }

    @Override
    public void send(List<MotorState> states, FeedbackSink feedback) throws IOException {
        long now = clock.nanoTime();
        for (MotorState s : states) {
            bot.command(s.running() ? LineBotProtocol.speed(s.port(), s.degreesPerSecond())
                    : LineBotProtocol.stop(s.port(), s.stopMode() == MotorState.StopMode.BRAKE));
            int i = ports.indexOf(s.port());
            commanded[i] = s;
            changedAt[i] = now;
        }
    }

    /** @return the motors that run, or stopped less than {@link #SETTLE_NANOS} ago */
    @Override
    public int poll(FeedbackSink feedback) throws IOException {
        int[] counts = bot.counts();
        long now = clock.nanoTime();
        int moving = 0;
        for (int i = 0; i < ports.size(); i++) {
            feedback.degrees(i, counts[ports.get(i).equals("A") ? 0 : 1]);
            MotorState m = commanded[i];
            if (m != null && (m.running() || now - changedAt[i] < SETTLE_NANOS)) {
                moving++;
            }
        }
        return moving;
    }

    @Override
    public LinkTiming timing() {
        return this;
    }

    /** Half the board's measured round trip. */
    @Override
    public long oneWayDelayNanos() {
        return bot.roundTrip().oneWayNanos();
    }

    /** The exchange under way on the channel (a poll, a sensor read): a stop waits for it. */
    @Override
    public long nanosUntilFree() {
        return bot.nanosUntilFree();
    }

    /**
     * Zeroes both encoders, so they count from the platform's start.
     *
     * @throws IOException if the link failed
     */
    void zero() throws IOException {
        bot.command(LineBotProtocol.zero());
    }
}
