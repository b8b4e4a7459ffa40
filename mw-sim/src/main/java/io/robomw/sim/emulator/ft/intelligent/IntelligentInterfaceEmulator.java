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
    private int motorByte;
    private long lastCommandNanos = System.nanoTime();
    private boolean watchdogTripped;
    private long watchdogTrips;
    private int digital;
    private int exValue;
    private int eyValue;

    /** A digital input that counts a wheel's impulse wheel. */
    private record Counter(int bit, String motorPort) {
    }

    /**
     * @param robot the simulated robot
     */
    public IntelligentInterfaceEmulator(SimMotors robot) {
        super("ft-intelligent", robot, framing());
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
        return bind(simulation, robotName, IntelligentInterfaceEmulator::new);
    }

    /** @return how often the watchdog switched the motors off for want of commands */
    public long watchdogTrips() {
        synchronized (firmware) {
            return watchdogTrips;
        }
    }

    /** @return whether any motor is switched on now */
    public boolean motorsOn() {
        synchronized (firmware) {
            for (int i = 0; i < motorPorts.length; i++) {
                if (IntelligentInterfaceTelegram.direction(motorByte, i) != 0) {
                    return true;
                }
            }
            return false;
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
            motorByte = frame[1] & 0xFF;
            lastCommandNanos = System.nanoTime();
            watchdogTripped = false;
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

    // ---- simulation thread ----

    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            if (!watchdogTripped && System.nanoTime() - lastCommandNanos > IntelligentInterfaceTelegram.WATCHDOG_MILLIS * 1_000_000L) {
                watchdogTripped = true;
                if (motorByte != 0) {
                    watchdogTrips++;
                }
                motorByte = 0;
            }
            for (int i = 0; i < motorPorts.length; i++) {
                if (motorPorts[i] == null) {
                    continue;
                }
                int direction = IntelligentInterfaceTelegram.direction(motorByte, i);
                double speed = direction == IntelligentInterfaceTelegram.CW ? FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER
                        : direction == IntelligentInterfaceTelegram.CCW ? -FtMotors.DEGREES_PER_SECOND_AT_FULL_POWER : 0;
                robot.command(motorPorts[i], speed);
            }
            int bits = 0;
            for (int bit = 0; bit < digitalSensors.length; bit++) {
                SensorSpec s = digitalSensors[bit];
                if (s != null && s.type() == SensorType.TOUCH && robot.siValue(s.name()) >= 0.5) {
                    bits |= 1 << bit;
                }
            }
            if (ticksPerRevolution > 0) {
                for (Counter c : counters) {
                    // The switch starts in the middle of a tooth, so the first transition comes after
                    // half a tick whichever way the wheel turns (a real one starts at an unknown phase,
                    // and half a tick is its average).
                    long tick = (long) Math.floor(robot.degrees(c.motorPort()) * ticksPerRevolution / 360.0 + 0.5);
                    if (Math.floorMod(tick, 2) == 1) {
                        bits |= 1 << c.bit();
                    }
                }
            }
            digital = bits;
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
            motorByte = 0;
            for (String port : motorPorts) {
                if (port != null) {
                    robot.command(port, 0);
                }
            }
        }
    }
}
