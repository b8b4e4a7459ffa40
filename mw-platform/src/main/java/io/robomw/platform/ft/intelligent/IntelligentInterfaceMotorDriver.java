package io.robomw.platform.ft.intelligent;

import io.robomw.api.spi.MotorChannel;
import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.brick.BrickChannel;
import io.robomw.api.Clock;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorState;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.util.Arrays;
import java.util.List;
import java.util.concurrent.locks.LockSupport;

import static io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram.ANALOG_EX;
import static io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram.ANALOG_EY;

/**
 * The Intelligent Interface's motor driver. The interface only switches motors on and off, has
 * no encoders, and stops its motors 300 ms after the last command, so:
 * <ul>
 *   <li>{@link #send} only records each motor's wanted duty (speed ÷ full speed);</li>
 *   <li>{@link #poll}, on the link side every cycle whatever the application does (it always
 *   reports work, so the link agent keeps the cycle's pace), sends the motor byte (keeping the interface alive) and reads the inputs back, alternating the EX and
 *   EY reads;</li>
 *   <li>a wheel's rotation comes from the impulse wheel on the digital input its description names
 *   ({@code counter: E1}), {@code encoder_ticks_per_revolution} switch transitions per motor turn,
 *   kept by an {@link ImpulseCounter} from the switch and the motor's on-time;</li>
 *   <li>on a serial line the wheels turn only inside <b>line-timed bursts</b>: one write of
 *   read-digital commands, each with the wheels that are on for its 2.1 ms, and a last command
 *   that switches them off. The interface takes each command as its bytes arrive, so a wheel is on
 *   exactly as long as its commands' bytes take, and never while the host is away, however late a
 *   loaded host gets to anything; and every command's answer shows the impulse switch, so
 *   transitions (36 ms apart at full speed) are read every 2.1 ms while a wheel turns. Each wheel
 *   is on in a share of the commands by its duty of the time since the last poll (the robot slows
 *   down when the host was away, and reaches about three quarters of full speed at most); a
 *   limited move is given no more commands than its rest needs, and its wheel is switched off on
 *   the link thread as its rotation reaches the limit (as a brick with a tacho limit would);</li>
 *   <li>over a TCP bridge, whose timing the host cannot know, each motor is on or off for a whole
 *   cycle by a sigma-delta over its duty; a poll that comes late after the motor passed two or
 *   more transitions still counts them from the motor's on-time; when the link thread has lately
 *   been away between cycles for longer than half a tick's time at full speed, wheel motors are
 *   pulsed (on for one exchange, at least {@code pulse_ms}, off with the next), and a limited move
 *   creeps over its last three ticks.</li>
 * </ul>
 * Positive speeds turn a motor clockwise ("right", bits {@code 10}). Time is the injected clock's:
 * a real robot's is the wall clock, which the interface's motors run on.
 */
public final class IntelligentInterfaceMotorDriver implements MotorDriver {

    private static final Logger LOG = LoggerFactory.getLogger(IntelligentInterfaceMotorDriver.class);

    /**
     * Over a TCP bridge: the share of the cycles in which a limited move's wheel is pulsed (on for
     * one exchange, off with the next) over its last {@link #CREEP_TICKS} ticks: it is never left
     * on across the link thread's wait between cycles, so a late cycle cannot carry it past its
     * target.
     */
    static final double CREEP_DUTY = 0.5;
    /** Ticks before a target at which a limited move creeps. */
    static final int CREEP_TICKS = 3;
    /** The least duty a creeping move slows to when polls come late. */
    static final double MIN_CREEP_DUTY = 0.05;
    /** How much the remembered poll gap shrinks at each poll (half-life about 35 polls, a third of a second). */
    private static final double GAP_DECAY = 0.98;

    private final BrickChannel channel;
    private final Clock clock;
    private final String robot;
    private final IntelligentInterfaceInputs inputs;
    /** Where the readings of the poll under way go; link side. */
    private FeedbackSink feedback;
    private final long pulseNanos;
    /** Whether the interface is on a serial line, whose byte timing times the wheels (not a TCP bridge). */
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
    /** Commands' wire times each counted wheel is owed on a serial line, by its duty, not yet sent. */
    private final double[] credit = new double[IntelligentInterfaceTelegram.MOTORS];
    private long lastPollStart = Long.MIN_VALUE;
    private long lineRoundTripNanos = Long.MAX_VALUE;
    private volatile long bursts;
    private volatile long wheelCommandsOn;

    /**
     * @param config      the platform configuration (motor ports M1..M4; which input counts which wheel)
     * @param channel     the channel to the interface
     * @param inputs      where the latest inputs are published for the sensor platform
     */
    public IntelligentInterfaceMotorDriver(PlatformConfig config, BrickChannel channel,
                                           IntelligentInterfaceInputs inputs) {
        this.channel = channel;
        this.clock = config.clock();
        this.robot = config.robotName();
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
    public LinkTiming timing() {
        return LinkTiming.NONE;
    }

    @Override
    public void send(List<MotorState> motors, FeedbackSink feedback) {
        for (MotorState m : motors) {
            int i = FtMotors.index(m.port(), IntelligentInterfaceTelegram.MOTORS);
            duty[i] = FtMotors.duty(m.degreesPerSecond());
            limit[i] = m.running() ? m.limitDegrees() : Double.POSITIVE_INFINITY;
            ticksAtStart[i] = counters[i] == null ? 0 : counters[i].ticks();
            credit[i] = 0;
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
     * Polls the interface. On a serial line, every cycle in which a wheel turns is one line-timed
     * burst ({@link #lineTimedBurst}): the wheels are never left on when the host stops watching.
     * Over a TCP bridge (whose timing the host cannot know) it polls once, with each motor on or off
     * for the cycle by its duty; a motor that reaches its target with the byte just sent on is
     * switched off at once with a second exchange; when the link thread has lately been away for
     * longer than half a tick's time at full speed between cycles (a loaded host), a wheel motor
     * that is due on is pulsed: on with one exchange and off again with the next.
     */
    @Override
    public int poll(FeedbackSink feedback) throws IOException {
        this.feedback = feedback;
        pollInterface();
        return 1; // the interface needs its motor byte every cycle, and its inputs are read at every poll
    }

    private void pollInterface() throws IOException {
        long now = clock.nanoTime();
        long sinceLastPoll = lastPollStart == Long.MIN_VALUE ? 0 : now - lastPollStart;
        lastPollStart = now;
        if (serialLine) {
            int[] slots = wheelSlots(sinceLastPoll);
            if (Arrays.stream(slots).max().orElse(0) > 0) {
                lineTimedBurst(slots);
            } else {
                exchange(nextMotorByte(unCounted()));
            }
            return;
        }
        if (lastServiceEnd != Long.MIN_VALUE) {
            recentServiceGap = Math.max(now - lastServiceEnd, (long) (recentServiceGap * GAP_DECAY));
        }
        boolean pulse = pulsing();
        int sent = nextMotorByte(ALL_MOTORS);
        int pulsed = wheelsOn(sent) & (pulse ? ALL_MOTORS : creeping());
        long pulseStart = clock.nanoTime();
        boolean reached = exchange(sent);
        if (pulsed != 0) {
            if (pulse) {
                pulses++;
            }
            // The action side unparks the link thread whenever it publishes: wait out the time.
            for (long left = pulseNanos - (clock.nanoTime() - pulseStart); left > 0;
                 left = pulseNanos - (clock.nanoTime() - pulseStart)) {
                LockSupport.parkNanos(this, left);
            }
            exchange(without(nextMotorByteAfterPulse(), pulsed));
        } else if (reached) {
            exchange(nextMotorByteAfterPulse());
        }
        lastServiceEnd = clock.nanoTime();
    }

    /**
     * How many of a burst's commands each counted wheel is on for: its duty of the time since the
     * last poll, in commands' wire times, owed and paid in whole commands (at most
     * {@link #burstSlots()} owed, so a host that was away does not make the wheel catch up: the
     * robot slows down instead), and for a limited move no more than its rest needs at full speed.
     *
     * @param sinceLastPoll nanoseconds since the last poll began
     * @return commands on, by motor
     */
    private int[] wheelSlots(long sinceLastPoll) {
        int[] slots = new int[duty.length];
        double elapsedSlots = sinceLastPoll / (double) COMMAND_WIRE_NANOS;
        for (int i = 0; i < duty.length; i++) {
            if (counters[i] == null) {
                continue;
            }
            if (duty[i] == 0) {
                credit[i] = 0;
                continue;
            }
            credit[i] = Math.min(burstSlots(), credit[i] + Math.abs(duty[i]) * elapsedSlots);
            int n = (int) Math.floor(credit[i]);
            if (Double.isFinite(limit[i])) {
                n = Math.min(n, (int) Math.ceil(Math.max(0, limit[i] - done(i)) / SLOT_DEGREES - 1e-9));
            }
            slots[i] = n;
            credit[i] -= n;
        }
        return slots;
    }

    /**
     * One cycle's wheel motion timed by the serial line itself. The wheels' commands and the one
     * that switches them off again go out in one write: {@code n} read-digital commands
     * ({@code C1}, answered with one byte), each with the wheels that are on for that command's
     * 2.1 ms, then one analog read ({@code C5} or {@code C9}, alternating) with every wheel off. The
     * interface takes each command as its two bytes arrive, so a wheel is on for exactly its
     * commands' wire time, however late the host gets to anything, and never while the host is
     * away; and each answer shows the impulse switch as its command arrived, every 2.1 ms while a
     * wheel turns (a tick takes 36 ms at full speed), so no transition is missed. Motors without a
     * counter keep their cycle's state through the burst.
     *
     * @param slots the commands each counted wheel is on for, from the first
     */
    private void lineTimedBurst(int[] slots) throws IOException {
        int held = nextMotorByte(unCounted());
        int on = Arrays.stream(slots).max().orElse(0);
        int count = on + 1;
        int[] commands = new int[count];
        int[] motorBytes = new int[count];
        byte[] request = new byte[2 * count];
        for (int k = 0; k < count; k++) {
            int motorByte = held;
            for (int i = 0; i < slots.length; i++) {
                if (k < slots[i]) {
                    motorByte = IntelligentInterfaceTelegram.withMotor(motorByte, i,
                            duty[i] > 0 ? IntelligentInterfaceTelegram.CW : IntelligentInterfaceTelegram.CCW);
                }
            }
            if (k < on) {
                commands[k] = IntelligentInterfaceTelegram.DIGITAL;
            } else {
                commands[k] = readEy ? ANALOG_EY : ANALOG_EX;
                readEy = !readEy;
            }
            motorBytes[k] = motorByte;
            System.arraycopy(IntelligentInterfaceTelegram.request(commands[k], motorByte), 0, request, 2 * k, 2);
        }
        for (int i = 0; i < slots.length; i++) {
            if (slots[i] > 0) {
                lastDirection[i] = duty[i] > 0 ? 1 : -1;
            }
        }
        long[] times = new long[3];
        byte[][] replies = channel.exchange((c, timeout) -> {
            // Taken once the channel is ours, before and after writing.
            times[0] = clock.nanoTime();
            c.send(request);
            times[1] = clock.nanoTime();
            byte[][] r = new byte[count][];
            for (int k = 0; k < count; k++) {
                r[k] = c.receiveExactly(IntelligentInterfaceTelegram.replyLength(commands[k]), timeout);
                if (k == 0) {
                    times[2] = clock.nanoTime();
                }
            }
            return r;
        });
        for (int k = 0; k < count; k++) {
            int digital = replies[k][0] & 0xFF;
            if (k == 0) {
                // The byte before this burst had every wheel off: its time does not move them.
                count(digital, times[0], times[1], times[2]);
                lastSentAt = times[0];
                lastWrittenAt = times[1];
                lastReceivedAt = times[2];
            } else {
                // The command before this one was in force for exactly one command's bytes.
                countFor(digital, COMMAND_WIRE_NANOS * (1 - WIRE_SLACK) / 1e9, COMMAND_WIRE_NANOS * (1 + WIRE_SLACK) / 1e9);
                lastSentAt += COMMAND_WIRE_NANOS;
                lastWrittenAt += COMMAND_WIRE_NANOS;
                lastReceivedAt += COMMAND_WIRE_NANOS;
            }
            if (commands[k] != IntelligentInterfaceTelegram.DIGITAL) {
                inputs.publish(digital, commands[k] == ANALOG_EX ? IntelligentInterfaceTelegram.analog(replies[k]) : -1,
                        commands[k] == ANALOG_EY ? IntelligentInterfaceTelegram.analog(replies[k]) : -1);
            } else {
                inputs.publish(digital, -1, -1);
            }
            lastMotorByte = motorBytes[k];
        }
        sampleLineRoundTrip(times[2] - times[1]);
        bursts++;
        wheelCommandsOn += on;
        enforceLimits(motorBytes[on]);
    }

    /** @return whether wheel motors are pulsed this cycle: the link thread has lately been away too long between cycles */
    private boolean pulsing() {
        double halfTickSeconds = 180.0 / ticksPerRevolution / FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER;
        return ticksPerRevolution > 0 && recentServiceGap / 1e9 > halfTickSeconds;
    }

    /**
     * The motor byte for this cycle: each motor of the mask on or off by its sigma-delta, the
     * others off.
     */
    private int nextMotorByte(int motors) {
        int motorByte = 0;
        for (int i = 0; i < duty.length; i++) {
            if ((motors & 1 << i) == 0) {
                continue;
            }
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

    /** @return the motors without an impulse counter, as a mask */
    private int unCounted() {
        int mask = 0;
        for (int i = 0; i < counters.length; i++) {
            if (counters[i] == null) {
                mask |= 1 << i;
            }
        }
        return mask;
    }

    /**
     * The most commands of a line-timed burst a wheel is on for: 16.7 ms of motion at 9600 baud.
     * A burst of n such commands and the one that switches the wheels off keeps the line busy for
     * (n + 1) × 2.1 ms and its last answer comes 3.1 ms after that, so at full duty a wheel is on
     * about three quarters of the time (full speed is not reached on a serial line; a longer burst
     * would come closer but leave the platform's commands waiting longer).
     */
    static final int BURST_SLOTS = 8;
    /** The most commands a wheel is on for in a burst over a link with latency: 267 ms. */
    static final int MAX_BURST_SLOTS = 128;

    /**
     * The commands a wheel may be on for in one burst: {@link #BURST_SLOTS}, or as many as fill the
     * link's own round trip on a link with latency (a serial adapter over Bluetooth, say), whose
     * bursts cannot come more often, so that the wheels keep their speed there too.
     */
    private int burstSlots() {
        long rt = lineRoundTripNanos;
        if (rt == Long.MAX_VALUE) {
            return BURST_SLOTS;
        }
        return (int) Math.max(BURST_SLOTS, Math.min(MAX_BURST_SLOTS, rt / COMMAND_WIRE_NANOS));
    }

    /**
     * Keeps the link's own round trip: the least time from a write to its first answer lately (a
     * host held up in between only makes a sample longer), rising slowly when the least grows.
     */
    private void sampleLineRoundTrip(long nanos) {
        long rt = lineRoundTripNanos;
        lineRoundTripNanos = rt == Long.MAX_VALUE || nanos < rt ? nanos : rt + (nanos - rt) / 64;
    }

    /**
     * The shortest pulse over a TCP bridge by default, milliseconds: a pulse lasts an exchange, and
     * at least this long (the link thread waits the rest). {@code connection: { pulse_ms: N }}
     * lengthens it for motors that need more to get going. On a serial line the bursts' commands
     * time the wheels instead.
     */
    static final int DEFAULT_PULSE_MILLIS = 5;

    /** The time a command's two bytes take at the interface's 9600 baud, 10 bits each. */
    static final long COMMAND_WIRE_NANOS = 2L * 10 * 1_000_000_000L / IntelligentInterfaceTelegram.BAUD;
    /** Degrees a motor at full power turns in one command's wire time: 1.3°. */
    static final double SLOT_DEGREES = FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER * COMMAND_WIRE_NANOS / 1e9;
    /** How far a line's actual bit timing may stray. */
    private static final double WIRE_SLACK = 0.05;

    /**
     * One exchange: a motor byte, the inputs back.
     *
     * @param motorByte the motors' state from now on
     * @return whether a motor that the byte switched on has reached its target
     */
    private boolean exchange(int motorByte) throws IOException {
        int command = readEy ? ANALOG_EY : ANALOG_EX;
        readEy = !readEy;
        byte[] request = IntelligentInterfaceTelegram.request(command, motorByte);
        long[] sent = new long[2];
        byte[] reply = channel.exchange((c, timeout) -> {
            // Taken once the channel is ours (a sensor read may have held it), before and after
            // writing: a host held up in between writes late.
            sent[0] = clock.nanoTime();
            c.send(request);
            sent[1] = clock.nanoTime();
            return c.receiveExactly(3, timeout);
        });
        long sentAt = sent[0];
        long writtenAt = sent[1];
        // The interface took the command, and sampled its inputs, between sending and receiving.
        long receivedAt = clock.nanoTime();
        sampleLineRoundTrip(receivedAt - writtenAt);
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
                        robot, Math.round(mostOn * 1000), portOf[motor], counter.recovered() - before);
            }
            feedback.degrees(portOf[motor], counter.ticks() * 360.0 / ticksPerRevolution);
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

    /** @return line-timed bursts sent (serial line: cycles in which a wheel turned) */
    public long bursts() {
        return bursts;
    }

    /** @return commands of line-timed bursts that had a wheel on */
    public long wheelCommandsOn() {
        return wheelCommandsOn;
    }

    /** @return the longest time between two polls so far, nanoseconds */
    public long longestPollGapNanos() {
        return longestGap;
    }
}
