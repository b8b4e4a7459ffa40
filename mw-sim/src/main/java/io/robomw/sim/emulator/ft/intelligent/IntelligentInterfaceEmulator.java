package io.robomw.sim.emulator.ft.intelligent;

import io.robomw.api.SensorType;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.ft.FtMotors;
import io.robomw.platform.ft.intelligent.IntelligentInterfaceTelegram;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.LinkModel;
import io.robomw.sim.emulator.Framing;

import java.util.ArrayList;
import java.util.List;
import java.util.Optional;

/**
 * A virtual fischertechnik Intelligent Interface 30402 on a serial device, bound to a robot in a
 * simulated world: 2-byte commands answered with 1 or 3 bytes (digital inputs, EX, EY big-endian),
 * motors on or off in either direction at {@link FtMotors#DEGREES_PER_SECOND_AT_FULL_POWER}, and the
 * interface's watchdog: motors off when no command came for 300 ms (wall-clock time, as the
 * hardware's timer).
 *
 * <h2>Real time on a loaded host</h2>
 * The interface's motors run in real time whatever the host does. The emulator keeps the motor
 * byte's history by wall-clock time ({@link MotorByteHistory}) and moves the simulated wheels by
 * it: each world step drives each motor for the time it was on during the wall-clock interval that
 * step stands for (the steps of a simulation catching up after its thread was held up stand for
 * the past), so the world follows the commands one step late but exactly. A command is answered
 * with the impulse switches as they are at that moment: the wheel's rotation at the last step,
 * moved on by the motor's on-time since.
 *
 * <p>Inputs: a wheel's {@code counter:} input shows its impulse wheel, one transition per
 * {@code 360 / encoder_ticks_per_revolution} degrees of the simulated motor, starting mid-tooth; a touch sensor on a
 * digital input reads closed when touching; a sensor on EX or EY gives the 10-bit value that its
 * description's conversion turns back into the true distance or brightness. The extension-module
 * commands (C2, C6, CA) answer with an extension that has nothing connected.
 */
public final class IntelligentInterfaceEmulator extends BrickEmulator {

    private final Object firmware = new Object();
    private final String[] motorPorts = new String[IntelligentInterfaceTelegram.MOTORS];
    private final List<Counter> counters = new ArrayList<>();
    private final SensorSpec[] digitalSensors = new SensorSpec[IntelligentInterfaceTelegram.INPUTS];
    private final SensorSpec ex;
    private final SensorSpec ey;
    private final int ticksPerRevolution;
    private final MotorByteHistory motorBytes = new MotorByteHistory();
    private final Shaft[] shafts = new Shaft[IntelligentInterfaceTelegram.MOTORS];
    private final double stepSeconds;
    /** The wall-clock time the last step stood for: where the next step's window starts. */
    private long lastStepWall = Long.MIN_VALUE;
    private int switches;
    private int exValue;
    private int eyValue;

    /** A digital input that counts a wheel's impulse wheel. */
    private record Counter(int bit, String motorPort) {
    }

    /**
     * One motor's shaft as the interface drives it in real time, against the simulated wheel it
     * turns: {@code driven} is the rotation its on-time gave up to the last step (by wall-clock
     * time), {@code commanded} what the world has been asked to turn the wheel so far, and the last
     * two steps' requests, which the world has not carried out yet (a commanded speed moves the
     * body in the step after next). A wheel that the world holds back (a wall) falls behind, as a
     * stalled motor does.
     */
    private static final class Shaft {
        double driven;
        double commanded;
        double wheel;
        double requestedLastStep;
        double requestedStepBefore;
        /** The impulse wheel's rotation as its switch last showed it, and when ({@link Long#MIN_VALUE} before the first). */
        double impulseWheel;
        long impulseWheelAt = Long.MIN_VALUE;

        /** @return the rotation the world's wheel has been asked for and has had the time to carry out */
        double carriedOut() {
            return commanded - requestedLastStep - requestedStepBefore;
        }
    }

    /**
     * @param robot       the simulated robot
     * @param stepSeconds the world's physics step, seconds
     */
    public IntelligentInterfaceEmulator(SimMotors robot, double stepSeconds) {
        super("ft-intelligent", robot, framing());
        if (!(stepSeconds > 0)) {
            throw new IllegalArgumentException("stepSeconds must be > 0, got " + stepSeconds);
        }
        this.stepSeconds = stepSeconds;
        for (int i = 0; i < shafts.length; i++) {
            shafts[i] = new Shaft();
        }
        RobotDescription d = robot.robot().description();
        for (int i = 0; i < motorPorts.length; i++) {
            String port = "M" + (i + 1);
            motorPorts[i] = d.motorPorts().contains(port) ? port : null;
        }
        ticksPerRevolution = d.drive().map(DifferentialDrive::encoderTicksPerRevolution).orElse(0);
        d.drive().ifPresent(drive -> {
            for (DifferentialDrive.Wheel w : List.of(drive.left(), drive.right())) {
                w.counter().ifPresent(c -> counters.add(new Counter(IntelligentInterfaceTelegram.digitalInput(c), w.port())));
            }
        });
        for (SensorSpec s : d.sensors()) {
            int bit = IntelligentInterfaceTelegram.digitalInput(s.port());
            if (bit >= 0) {
                digitalSensors[bit] = s;
            }
        }
        ex = sensorOn(d, "EX").orElse(null);
        ey = sensorOn(d, "EY").orElse(null);
    }

    private static Optional<SensorSpec> sensorOn(RobotDescription d, String port) {
        return d.sensors().stream().filter(s -> s.port().equals(port)).findFirst();
    }

    /** Commands are delimited by their first byte: 2 bytes for C1/C5/C9, 3 with the extension. */
    private static Framing framing() {
        return new Framing() {
            @Override
            public byte[] read(Reader in) throws java.io.IOException {
                byte[] first = in.readExactly(1);
                if (first == null) {
                    return null;
                }
                int length = IntelligentInterfaceTelegram.requestLength(first[0] & 0xFF);
                if (length < 0) {
                    throw new MalformedFrameException(String.format("0x%02X is not an Intelligent Interface command", first[0] & 0xFF));
                }
                byte[] rest = in.readExactly(length - 1);
                if (rest == null) {
                    return null;
                }
                byte[] frame = new byte[length];
                frame[0] = first[0];
                System.arraycopy(rest, 0, frame, 1, rest.length);
                return frame;
            }

            @Override
            public byte[] encode(byte[] reply) {
                return reply;
            }
        };
    }

    /**
     * Binds an emulator to a robot of a simulation and steps it with the world.
     *
     * @param simulation the simulation (the robot must be one it emulates)
     * @param robotName  the robot
     * @return the emulator, not yet serving; closing it unbinds it
     */
    public static IntelligentInterfaceEmulator bind(Simulation simulation, String robotName) {
        return bind(simulation, robotName, motors -> new IntelligentInterfaceEmulator(motors, simulation.world().stepSeconds()));
    }

    /** @return how often the watchdog switched the motors off for want of commands */
    public long watchdogTrips() {
        synchronized (firmware) {
            return motorBytes.watchdogTrips(System.nanoTime());
        }
    }

    /**
     * @return whether the world's wheels have caught up with the interface's motors: every wheel
     *         has been asked for all the rotation its motor's on-time gave up to the last step, and
     *         the world has had the time to carry it out (a simulation held up by a loaded host
     *         lags behind the interface's real-time motors until then)
     */
    public boolean worldCaughtUp() {
        synchronized (firmware) {
            for (Shaft shaft : shafts) {
                if (Math.abs(shaft.driven - shaft.commanded) > CAUGHT_UP_DEGREES || shaft.requestedLastStep != 0 || shaft.requestedStepBefore != 0) {
                    return false;
                }
            }
            return true;
        }
    }

    /** Rotation owed to a wheel that counts as none. */
    private static final double CAUGHT_UP_DEGREES = 0.5;

    /** @return whether any motor is switched on now */
    public boolean motorsOn() {
        synchronized (firmware) {
            return motorBytes.at(System.nanoTime()) != 0;
        }
    }

    /** The interface's RS-232 line: 9600 baud, 8N1, no latency beyond the bytes' time. */
    @Override
    protected LinkModel defaultLinkModel() {
        return LinkModel.serial(IntelligentInterfaceTelegram.BAUD, 10);
    }

    // ---- I/O thread ----

    @Override
    protected byte[] handle(byte[] frame) {
        int command = frame[0] & 0xFF;
        synchronized (firmware) {
            long now = frameArrivalNanos();
            record(now, frame[1] & 0xFF);
            int digital = digitalAt(now);
            return switch (command) {
                case IntelligentInterfaceTelegram.DIGITAL -> new byte[]{(byte) digital};
                case IntelligentInterfaceTelegram.ANALOG_EX -> new byte[]{(byte) digital, (byte) (exValue >> 8), (byte) exValue};
                case IntelligentInterfaceTelegram.ANALOG_EY -> new byte[]{(byte) digital, (byte) (eyValue >> 8), (byte) eyValue};
                case IntelligentInterfaceTelegram.EXT_DIGITAL -> new byte[]{(byte) digital, 0};
                case IntelligentInterfaceTelegram.EXT_ANALOG_EX -> new byte[]{(byte) digital, 0, (byte) (exValue >> 8), (byte) exValue};
                case IntelligentInterfaceTelegram.EXT_ANALOG_EY -> new byte[]{(byte) digital, 0, (byte) (eyValue >> 8), (byte) eyValue};
                default -> throw new IllegalArgumentException(String.format("0x%02X is not an Intelligent Interface command", command));
            };
        }
    }

    /**
     * Records a command that arrived at a wall-clock time. A command can arrive before the wall
     * time the last world step stood for (the emulator's thread got to it after that step): the
     * motors' rotation up to that step, counted with the byte in force before, is corrected.
     */
    private void record(long at, int motorByte) {
        boolean late = lastStepWall != Long.MIN_VALUE && at < lastStepWall;
        double[] before = new double[shafts.length];
        if (late) {
            for (int i = 0; i < shafts.length; i++) {
                before[i] = degreesDriven(i, at, lastStepWall);
            }
        }
        motorBytes.command(at, motorByte);
        if (late) {
            for (int i = 0; i < shafts.length; i++) {
                shafts[i].driven += degreesDriven(i, at, lastStepWall) - before[i];
            }
        }
    }

    /**
     * The digital inputs at a wall-clock time: the switches as the last step saw them, and each
     * impulse wheel's switch at the rotation the motor's on-time has given it by now (less what the
     * world held the wheel back by).
     *
     * <p>The impulse wheel sits on the motor's shaft, so it turns only while the motor is on, and
     * only the way the motor turns: where the world's wheel falls short of what it was asked for
     * (a wall, or the body's top speed a hair under the motor's), the shaft waits until the motor
     * has made up for it, rather than turning back. A switch that turned back across an edge would
     * show two transitions that the real wheel never made.
     */
    private int digitalAt(long now) {
        int bits = switches;
        if (ticksPerRevolution > 0 && lastStepWall != Long.MIN_VALUE) {
            for (Counter c : counters) {
                int motor = motorIndex(c.motorPort());
                Shaft shaft = shafts[motor];
                // A command may be answered at a time before the last step's: its rotation then is
                // the last step's, less the motor's on-time since.
                double drivenNow = shaft.driven + (now >= lastStepWall ? degreesDriven(motor, lastStepWall, now)
                        : -degreesDriven(motor, now, lastStepWall));
                double degrees = shaft.wheel + drivenNow - shaft.carriedOut();
                if (shaft.impulseWheelAt == Long.MIN_VALUE) {
                    shaft.impulseWheel = degrees;
                } else if (now > shaft.impulseWheelAt) {
                    double on = motorBytes.signedOnSeconds(motor, shaft.impulseWheelAt, now);
                    if (on > 0) {
                        shaft.impulseWheel = Math.max(shaft.impulseWheel, degrees);
                    } else if (on < 0) {
                        shaft.impulseWheel = Math.min(shaft.impulseWheel, degrees);
                    }
                }
                shaft.impulseWheelAt = Math.max(shaft.impulseWheelAt, now);
                if (impulseSwitchClosed(shaft.impulseWheel)) {
                    bits |= 1 << c.bit();
                }
            }
        }
        return bits;
    }

    /**
     * The switch starts in the middle of a tooth, so the first transition comes after half a tick
     * whichever way the wheel turns (a real one starts at an unknown phase, and half a tick is its
     * average).
     */
    private boolean impulseSwitchClosed(double degrees) {
        long tick = (long) Math.floor(degrees * ticksPerRevolution / 360.0 + 0.5);
        return Math.floorMod(tick, 2) == 1;
    }

    private int motorIndex(String port) {
        for (int i = 0; i < motorPorts.length; i++) {
            if (port.equals(motorPorts[i])) {
                return i;
            }
        }
        return -1;
    }

    // ---- simulation thread ----

    /** Degrees a motor's on-time in a wall-clock interval turns it (counter-clockwise negative). */
    private double degreesDriven(int motor, long from, long to) {
        return FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER * simulatedSecondsPerSecond() * motorBytes.signedOnSeconds(motor, from, to);
    }

    /**
     * Adds the wall-clock window since the last step ({@code [last, wall)}) to each motor's driven
     * rotation, and asks the world to turn the wheel by what it still owes (at most full speed, so
     * a world catching up after its thread was held up pays the debt over the next steps), then
     * samples the inputs.
     */
    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            long wall = stepWallNanos();
            long from = lastStepWall == Long.MIN_VALUE ? wall : lastStepWall;
            for (int i = 0; i < motorPorts.length; i++) {
                if (motorPorts[i] == null) {
                    continue;
                }
                Shaft shaft = shafts[i];
                shaft.driven += degreesDriven(i, from, wall);
                double owed = shaft.driven - shaft.commanded;
                double speed = Math.max(-FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER,
                        Math.min(FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER, owed / stepSeconds));
                robot.command(motorPorts[i], speed);
                shaft.requestedStepBefore = shaft.requestedLastStep;
                shaft.requestedLastStep = speed * stepSeconds;
                shaft.commanded += speed * stepSeconds;
                shaft.wheel = robot.degrees(motorPorts[i]);
            }
            int bits = 0;
            for (int bit = 0; bit < digitalSensors.length; bit++) {
                SensorSpec s = digitalSensors[bit];
                if (s != null && s.type() == SensorType.TOUCH && robot.siValue(s.name()) >= 0.5) {
                    bits |= 1 << bit;
                }
            }
            lastStepWall = wall;
            switches = bits;
            exValue = analog(robot, ex);
            eyValue = analog(robot, ey);
        }
    }

    private static int analog(SimMotors robot, SensorSpec sensor) {
        if (sensor == null) {
            return 1023;
        }
        double raw = sensor.conversion().invert(robot.siValue(sensor.name()));
        return (int) Math.max(0, Math.min(1023, Math.round(raw)));
    }

    @Override
    protected void halt(SimMotors robot) {
        synchronized (firmware) {
            motorBytes.command(System.nanoTime(), 0);
            for (String port : motorPorts) {
                if (port != null) {
                    robot.command(port, 0);
                }
            }
        }
    }
}
