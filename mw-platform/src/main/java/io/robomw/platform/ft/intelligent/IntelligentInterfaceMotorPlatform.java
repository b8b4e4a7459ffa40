package io.robomw.platform.ft.intelligent;

import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.motor.MotorState;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.List;
import java.util.concurrent.locks.LockSupport;

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
 *   <li>a wheel's rotation comes from the impulse wheel on the digital input its description names
 *   ({@code counter: E1}), {@code encoder_ticks_per_revolution} switch transitions per motor turn,
 *   kept by an {@link ImpulseCounter} from the switch and the motor's on-time: a poll that comes
 *   late (a loaded host) after the motor passed two or more transitions still counts them, and
 *   between transitions the rotation moves on with the motor;</li>
 *   <li>when the link thread has lately been away between cycles for longer than half a tick's
 *   time at full speed (a loaded host), wheel motors are pulsed: on for one exchange, off with the
 *   next, so none runs unwatched through the thread's absence; the robot slows down meanwhile;</li>
 *   <li>a limited move creeps over its last three ticks, its wheel pulsed in at most half the
 *   cycles (fewer when polls have lately come further apart than half a tick's time at full
 *   speed); the link thread stops it
 *   itself when its rotation reaches the limit (as a brick with a tacho limit would), at once with
 *   an extra exchange if the byte just sent had the motor on, so neither a busy action thread nor
 *   a late poll lets it run on.</li>
 * </ul>
 * Positive speeds turn a motor clockwise ("right", bits {@code 10}). Time is the injected clock's:
 * a real robot's is the wall clock, which the interface's motors run on.
 */
public final class IntelligentInterfaceMotorPlatform extends GenericMotorPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(IntelligentInterfaceMotorPlatform.class);

    /**
     * Share of the cycles in which a limited move's wheel is pulsed (on for one exchange, off with
     * the next) over its last {@link #CREEP_TICKS} ticks: it is never left on across the link
     * thread's wait between cycles, so a late cycle cannot carry it past its target.
     */
    static final double CREEP_DUTY = 0.5;
    /** Ticks before a target at which a limited move creeps. */
    static final int CREEP_TICKS = 3;
    /** The least duty a creeping move slows to when polls come late. */
    static final double MIN_CREEP_DUTY = 0.05;
    /** How much the remembered poll gap shrinks at each poll (half-life about 35 polls, a third of a second). */
    private static final double GAP_DECAY = 0.98;

    private final BrickChannel channel;
    private final IntelligentInterfaceInputs inputs;
    private final long pulseNanos;
    /** Whether the interface is on a serial line, whose byte timing times pulses (not a TCP bridge). */
    private final boolean serialLine;
    private final int ticksPerRevolution;
    private final double[] duty = new double[IntelligentInterfaceTelegram.MOTORS];
    private final double[] accumulator = new double[IntelligentInterfaceTelegram.MOTORS];
    private final int[] lastDirection = new int[IntelligentInterfaceTelegram.MOTORS];
    private final String[] portOf = new String[IntelligentInterfaceTelegram.MOTORS];
    private final int[] counterBit = {-1, -1, -1, -1};
    private final ImpulseCounter[] counters = new ImpulseCounter[IntelligentInterfaceTelegram.MOTORS];
    private final double[] limit = new double[IntelligentInterfaceTelegram.MOTORS];
    private final double[] ticksAtStart = new double[IntelligentInterfaceTelegram.MOTORS];
    private int previousDigital = -1;
    private boolean readEy;
    private long lastSentAt = Long.MIN_VALUE;
    private long lastWrittenAt = Long.MIN_VALUE;
    private long lastReceivedAt = Long.MIN_VALUE;
    private int lastMotorByte;
    private long recentGap;
    private long recentServiceGap;
    private long lastServiceEnd = Long.MIN_VALUE;
    private volatile long longestGap;
    private volatile long pulses;

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
        this.serialLine = config.connection().text("host").isEmpty();
        int pulseMillis = config.connection().integer("pulse_ms", DEFAULT_PULSE_MILLIS);
        if (pulseMillis < 0 || pulseMillis > 100) {
            throw new IllegalArgumentException(config.source() + ": connection.pulse_ms must be 0..100 milliseconds, got " + pulseMillis);
        }
        this.pulseNanos = pulseMillis * 1_000_000L;
        for (String port : config.motorPorts()) {
            portOf[FtMotors.index(port, IntelligentInterfaceTelegram.MOTORS)] = port;
        }
        this.ticksPerRevolution = config.wheels().stream().mapToInt(MotorChannel::encoderTicksPerRevolution).max().orElse(0);
        for (MotorChannel w : config.wheels()) {
            w.counter().ifPresent(c -> {
                int bit = IntelligentInterfaceTelegram.digitalInput(c);
                if (bit < 0) {
                    throw new IllegalArgumentException(config.source() + ": wheel counter '" + c
                            + "' must be a digital input of the Intelligent Interface, E1 to E8");
                }
                int motor = FtMotors.index(w.port(), IntelligentInterfaceTelegram.MOTORS);
                counterBit[motor] = bit;
                if (ticksPerRevolution > 0) {
                    counters[motor] = new ImpulseCounter(ticksPerRevolution, FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER);
                }
            });
        }
    }

    @Override
    public boolean hasEncoder(String port) {
        return counters[FtMotors.index(port, IntelligentInterfaceTelegram.MOTORS)] != null;
    }

    @Override
    protected void runImpl(List<MotorState> motors) {
        for (MotorState m : motors) {
            int i = FtMotors.index(m.port(), IntelligentInterfaceTelegram.MOTORS);
            duty[i] = FtMotors.duty(m.degreesPerSecond());
            limit[i] = m.running() ? m.limitDegrees() : Double.POSITIVE_INFINITY;
            ticksAtStart[i] = counters[i] == null ? 0 : counters[i].ticks();
        }
    }

    /** @return degrees a counted motor has turned since its state was last set */
    private double done(int motor) {
        return Math.abs(counters[motor].ticks() - ticksAtStart[motor]) * 360.0 / ticksPerRevolution;
    }

    /**
     * The duty for this cycle: the wanted one, but at most {@link #creepDuty()} within
     * {@link #CREEP_TICKS} ticks of a limited move's end, where the wheel is pulsed.
     */
    private double cycleDuty(int i) {
        double d = Math.abs(duty[i]);
        if (creeps(i)) {
            d = Math.min(d, creepDuty());
        }
        return d;
    }

    /**
     * The duty of a limited move's last ticks: {@link #CREEP_DUTY}, or less when polls have lately
     * come further apart than half a tick's time at full speed (a loaded host): a motor left on
     * over such a gap runs past its target, so the move slows down until the gaps are gone.
     */
    private double creepDuty() {
        double tickSeconds = 360.0 / ticksPerRevolution / FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER;
        double gapSeconds = recentGap / 1e9;
        if (gapSeconds <= 0) {
            return CREEP_DUTY;
        }
        return Math.max(MIN_CREEP_DUTY, Math.min(CREEP_DUTY, tickSeconds / (2 * gapSeconds)));
    }

    /**
     * Polls the interface. Normally once, with each motor on or off for the cycle by its duty; a
     * motor that reaches its target with the byte just sent on is switched off at once with a
     * second exchange. When the link thread has lately been away for longer than half a tick's
     * time at full speed between cycles (a loaded host), a wheel motor that is due on is pulsed:
     * on with one exchange and off again with the next, so it never runs unwatched through the
     * thread's absence; the robot slows down until the gaps are gone.
     */
    @Override
    protected void pollFeedback() throws IOException {
        long now = clock().nanoTime();
        if (lastServiceEnd != Long.MIN_VALUE) {
            recentServiceGap = Math.max(now - lastServiceEnd, (long) (recentServiceGap * GAP_DECAY));
        }
        boolean pulse = pulsing();
        int sent = nextMotorByte();
        int pulsed = wheelsOn(sent) & (pulse ? ALL_MOTORS : creeping());
        if (pulsed != 0 && serialLine) {
            if (pulse) {
                pulses++;
            }
            if (burst(sent, without(sent, pulsed))) {
                poll(nextMotorByteAfterPulse());
            }
            lastServiceEnd = clock().nanoTime();
            return;
        }
        long pulseStart = clock().nanoTime();
        boolean reached = poll(sent);
        if (pulsed != 0) {
            if (pulse) {
                pulses++;
            }
            // The action side unparks the link thread whenever it publishes: wait out the time.
            for (long left = pulseNanos - (clock().nanoTime() - pulseStart); left > 0;
                 left = pulseNanos - (clock().nanoTime() - pulseStart)) {
                LockSupport.parkNanos(this, left);
            }
            poll(without(nextMotorByteAfterPulse(), pulsed));
        } else if (reached) {
            poll(nextMotorByteAfterPulse());
        }
        lastServiceEnd = clock().nanoTime();
    }

    /** @return whether wheel motors are pulsed this cycle: the link thread has lately been away too long between cycles */
    private boolean pulsing() {
        double halfTickSeconds = 180.0 / ticksPerRevolution / FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER;
        return ticksPerRevolution > 0 && recentServiceGap / 1e9 > halfTickSeconds;
    }

    /** The motor byte for this cycle: each motor on or off by its sigma-delta. */
    private int nextMotorByte() {
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
        return motorByte;
    }

    /** The byte for a second exchange in the same cycle: the last one, less every motor stopped since. */
    private int nextMotorByteAfterPulse() {
        int motorByte = lastMotorByte;
        for (int i = 0; i < duty.length; i++) {
            if (duty[i] == 0) {
                motorByte = IntelligentInterfaceTelegram.withMotor(motorByte, i, 0);
            }
        }
        return motorByte;
    }

    private int wheelsOn(int motorByte) {
        int on = 0;
        for (int i = 0; i < counters.length; i++) {
            if (counters[i] != null && IntelligentInterfaceTelegram.direction(motorByte, i) != 0) {
                on |= 1 << i;
            }
        }
        return on;
    }

    /** @return the motors whose bits are set in the mask switched off in a motor byte */
    private static int without(int motorByte, int motors) {
        for (int i = 0; i < IntelligentInterfaceTelegram.MOTORS; i++) {
            if ((motors & 1 << i) != 0) {
                motorByte = IntelligentInterfaceTelegram.withMotor(motorByte, i, 0);
            }
        }
        return motorByte;
    }

    /** @return the counted motors within {@link #CREEP_TICKS} of a limited move's end, as a mask */
    private int creeping() {
        int mask = 0;
        for (int i = 0; i < counters.length; i++) {
            if (creeps(i)) {
                mask |= 1 << i;
            }
        }
        return mask;
    }

    private boolean creeps(int i) {
        return counters[i] != null && Double.isFinite(limit[i]) && limit[i] - done(i) <= CREEP_TICKS * 360.0 / ticksPerRevolution;
    }

    private static final int ALL_MOTORS = (1 << IntelligentInterfaceTelegram.MOTORS) - 1;
    /**
     * The shortest pulse by default, milliseconds: a command and its reply take 5.2 ms at 9600
     * baud, and a pulse lasts at least that long on any link (over a faster bridge the link thread
     * waits the rest). {@code connection: { pulse_ms: N }} lengthens it for motors that need more
     * to get going.
     */
    static final int DEFAULT_PULSE_MILLIS = 5;

    /**
     * A pulse timed by the line itself: the commands that switch the pulsed wheels on and the one
     * that switches them off go out in one write, so the interface, taking each as its two bytes
     * arrive, keeps the wheels on for exactly their bytes' time (2.1 ms a command at 9600 baud),
     * however late the host gets to anything. Every command is answered; each answer shows the
     * switches as its command arrived.
     *
     * @param on  the byte that switches the pulsed wheels on
     * @param off the same with them off
     * @return whether a motor still on after the pulse has reached its target
     */
    private boolean burst(int on, int off) throws IOException {
        int onCommands = (int) Math.max(1, (pulseNanos + COMMAND_WIRE_NANOS - 1) / COMMAND_WIRE_NANOS);
        int count = onCommands + 1;
        int[] commands = new int[count];
        byte[] request = new byte[2 * count];
        for (int i = 0; i < count; i++) {
            commands[i] = readEy ? ANALOG_EY : ANALOG_EX;
            readEy = !readEy;
            byte[] one = IntelligentInterfaceTelegram.request(commands[i], i < onCommands ? on : off);
            System.arraycopy(one, 0, request, 2 * i, 2);
        }
        long[] times = new long[2 + count];
        byte[][] replies = channel.exchange((c, timeout) -> {
            times[0] = clock().nanoTime();
            c.send(request);
            times[1] = clock().nanoTime();
            byte[][] r = new byte[count][];
            for (int i = 0; i < count; i++) {
                r[i] = c.receiveExactly(3, timeout);
                times[2 + i] = clock().nanoTime();
            }
            return r;
        });
        for (int i = 0; i < count; i++) {
            int digital = replies[i][0] & 0xFF;
            inputs.publish(digital, commands[i] == ANALOG_EX ? IntelligentInterfaceTelegram.analog(replies[i]) : -1,
                    commands[i] == ANALOG_EY ? IntelligentInterfaceTelegram.analog(replies[i]) : -1);
            if (i == 0) {
                count(digital, times[0], times[1], times[2]);
                lastSentAt = times[0];
                lastWrittenAt = times[1];
                lastReceivedAt = times[2];
            } else {
                // The command before this one was in force for exactly one command's bytes.
                countFor(digital, COMMAND_WIRE_NANOS * (1 - WIRE_SLACK) / 1e9, COMMAND_WIRE_NANOS * (1 + WIRE_SLACK) / 1e9);
                lastSentAt += COMMAND_WIRE_NANOS;
                lastWrittenAt += COMMAND_WIRE_NANOS;
                lastReceivedAt = Math.max(lastReceivedAt + COMMAND_WIRE_NANOS, times[2 + i]);
            }
            lastMotorByte = i < onCommands ? on : off;
        }
        return enforceLimits(off);
    }

    /** The time a command's two bytes take at the interface's 9600 baud, 10 bits each. */
    static final long COMMAND_WIRE_NANOS = 2L * 10 * 1_000_000_000L / IntelligentInterfaceTelegram.BAUD;
    /** How far a line's actual bit timing may stray. */
    private static final double WIRE_SLACK = 0.05;

    /**
     * One exchange: a motor byte, the inputs back.
     *
     * @param motorByte the motors' state from now on
     * @return whether a motor that the byte switched on has reached its target
     */
    private boolean poll(int motorByte) throws IOException {
        int command = readEy ? ANALOG_EY : ANALOG_EX;
        readEy = !readEy;
        byte[] request = IntelligentInterfaceTelegram.request(command, motorByte);
        long[] sent = new long[2];
        byte[] reply = channel.exchange((c, timeout) -> {
            // Taken once the channel is ours (a sensor read may have held it), before and after
            // writing: a host held up in between writes late.
            sent[0] = clock().nanoTime();
            c.send(request);
            sent[1] = clock().nanoTime();
            return c.receiveExactly(3, timeout);
        });
        long sentAt = sent[0];
        long writtenAt = sent[1];
        // The interface took the command, and sampled its inputs, between sending and receiving.
        long receivedAt = clock().nanoTime();
        int digital = reply[0] & 0xFF;
        inputs.publish(digital, command == ANALOG_EX ? IntelligentInterfaceTelegram.analog(reply) : -1,
                command == ANALOG_EY ? IntelligentInterfaceTelegram.analog(reply) : -1);
        count(digital, sentAt, writtenAt, receivedAt);
        lastSentAt = sentAt;
        lastWrittenAt = writtenAt;
        lastReceivedAt = receivedAt;
        lastMotorByte = motorByte;
        return enforceLimits(motorByte);
    }

    /**
     * Stops a limited move on the link thread as soon as its rotation reaches the limit, as a
     * brick with a tacho limit does by itself: the execution action thread stops it too, a cycle
     * later, but a motor the interface keeps on until the next command must not wait for that.
     *
     * @param sent the motor byte just sent
     * @return whether a motor that byte switched on was stopped
     */
    private boolean enforceLimits(int sent) {
        boolean stoppedRunning = false;
        for (int i = 0; i < duty.length; i++) {
            if (duty[i] != 0 && Double.isFinite(limit[i]) && counters[i] != null && done(i) >= limit[i]) {
                duty[i] = 0;
                accumulator[i] = 0;
                limit[i] = Double.POSITIVE_INFINITY;
                stoppedRunning |= IntelligentInterfaceTelegram.direction(sent, i) != 0;
            }
        }
        return stoppedRunning;
    }

    /**
     * Moves each counted wheel by this poll's switch and the on-time of the byte in force since
     * the last poll, and reports the wheels' rotation. The interface took each command between its
     * sending and the sooner of its reply and {@link #COMMAND_ARRIVES_WITHIN_NANOS} later, so the
     * last byte was in force for at least the time from the last command's latest arrival to this
     * sending, and at most from the last sending to this command's latest arrival.
     *
     * @param sentAt     when this poll's command was about to be written
     * @param writtenAt  when its writing returned
     * @param receivedAt when its reply came
     */
    private void count(int digital, long sentAt, long writtenAt, long receivedAt) {
        boolean first = lastSentAt == Long.MIN_VALUE;
        long interval = first ? 0 : sentAt - lastSentAt;
        double leastOn = first ? 0 : Math.max(0, sentAt - tookAtMost(lastWrittenAt, lastReceivedAt)) / 1e9;
        double mostOn = first ? 0 : (tookAtMost(writtenAt, receivedAt) - lastSentAt) / 1e9;
        longestGap = Math.max(longestGap, interval);
        recentGap = Math.max(interval, (long) (recentGap * GAP_DECAY));
        countFor(digital, leastOn, mostOn);
    }

    /**
     * Moves each counted wheel by a poll's switch and the least and most time the byte in force
     * before it was on, and reports the wheels' rotation.
     */
    private void countFor(int digital, double leastOn, double mostOn) {
        for (int motor = 0; motor < counters.length; motor++) {
            ImpulseCounter counter = counters[motor];
            if (counter == null) {
                continue;
            }
            int bit = 1 << counterBit[motor];
            boolean changed = previousDigital >= 0 && ((digital ^ previousDigital) & bit) != 0;
            int d = IntelligentInterfaceTelegram.direction(lastMotorByte, motor);
            int driven = d == IntelligentInterfaceTelegram.CW ? 1 : d == IntelligentInterfaceTelegram.CCW ? -1 : 0;
            long before = counter.recovered();
            counter.poll(changed, previousDigital >= 0 ? driven : 0, lastDirection[motor], leastOn, mostOn);
            if (counter.recovered() != before) {
                LOG.debug("robot '{}': a poll up to {} ms after the last with {} on: counted {} transitions its switch did not show",
                        robot(), Math.round(mostOn * 1000), portOf[motor], counter.recovered() - before);
            }
            reportDegrees(portOf[motor], counter.ticks() * 360.0 / ticksPerRevolution);
        }
        previousDigital = digital;
    }

    /**
     * The latest the interface can have taken a command: when its reply came, or
     * {@link #COMMAND_ARRIVES_WITHIN_NANOS} after it was written, whichever is sooner. The
     * interface itself never waits: a reply that comes later was held up on the host's side.
     */
    private static long tookAtMost(long writtenAt, long receivedAt) {
        return Math.min(receivedAt, writtenAt + COMMAND_ARRIVES_WITHIN_NANOS);
    }

    /**
     * How soon after it is written a command reaches the interface, at most: its two bytes take
     * 2.1 ms at 9600 baud; the rest allows for a USB serial adapter's buffering and for a loaded
     * host's kernel sending them late.
     */
    static final long COMMAND_ARRIVES_WITHIN_NANOS = 20_000_000L;

    /** @return transitions counted beyond what the switches showed, because polls came late */
    public long recoveredTicks() {
        long n = 0;
        for (ImpulseCounter c : counters) {
            n += c == null ? 0 : c.recovered();
        }
        return n;
    }

    /** @return cycles in which wheel motors were pulsed because the link thread had been away too long */
    public long pulses() {
        return pulses;
    }

    /** @return the longest time between two polls so far, nanoseconds */
    public long longestPollGapNanos() {
        return longestGap;
    }
}
