package io.robomw.sim.emulator.rcx;

import io.robomw.api.SensorType;
import io.robomw.config.description.DifferentialDrive;
import io.robomw.config.description.RobotDescription;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.rcx.RcxMotorDriver;
import io.robomw.platform.rcx.RcxPacket;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.Framing;
import io.robomw.sim.emulator.LinkModel;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.util.List;

/**
 * A virtual LEGO Mindstorms RCX (standard RIS firmware) behind a serial IR tower, on a
 * pseudo-terminal, bound to a robot in a simulated world. It answers the packets of
 * {@link RcxPacket}'s table as the brick does, and echoes every packet it hears first, as the
 * serial tower does (switch it off for a tower that does not echo):
 * <ul>
 *   <li>a packet with a bad complement or checksum is echoed but not answered (the brick ignores
 *   what it cannot read); an opcode it does not know likewise;</li>
 *   <li>a packet whose opcode byte equals the last one's is a retransmission: its reply is sent
 *   again, but it is not run again (senders flip the toggle bit, 0x08, to send a command twice);</li>
 *   <li><b>motors</b> A, B, C: Set motor power (steps 0..7, from a constant), Set motor direction
 *   (forward, reverse, flip), Set motor on/off (on, off braking, float); a motor that is on turns
 *   at (power + 1) / 8 of {@link RcxMotorDriver#DEGREES_PER_SECOND_AT_FULL_POWER}; at power-up
 *   every motor floats, forward, at power 7;</li>
 *   <li><b>sensors</b> S1..S3: the description's sensor on that input, and the rotation sensor
 *   of any wheel that names it as its {@code counter:}. Set sensor type and Set sensor mode
 *   (each clears the value); Get value of source 9 (value in the mode), 12 (raw 0..1023), 13
 *   (boolean), 10 (type), 11 (mode), 3 (a motor's state), 1 (timer, 1/100 s), 0 (variables, all 0).
 *   Raw values: a touch sensor 183 pressed, 1023 released; a light sensor 1023 − percent × 156 / 25
 *   for the floor's brightness; boolean mode 1 below raw 450, 0 above 570, unchanged between; percent
 *   mode (1023 − raw) × 25 / 156, 100 at raw 391 and below (Kekoa Proudfoot, RCX Internals); a
 *   rotation sensor counts 16 a turn of the wheel's motor shaft in angle mode;</li>
 *   <li>Get battery 9300 mV; Get versions ROM 3.1, firmware 3.28 (RIS 2.0); Alive, Play tone,
 *   Play sound, Stop all tasks are acknowledged.</li>
 * </ul>
 * The link is the tower's by default: 2400 baud, 11 bits a byte (8O1), so a packet, its echo and
 * its reply take about 0.12 s.
 *
 * <p>Threads: as {@link BrickEmulator}; the firmware state is guarded by one lock.
 */
public final class RcxEmulator extends BrickEmulator {

    /** What Get battery reports, millivolts. */
    public static final int BATTERY_MILLIVOLTS = 9300;
    private static final int OUTPUTS = 3;
    private static final int INPUTS = 3;
    private static final int RAW_PRESSED = 183;
    private static final int RAW_OPEN = 1023;
    private static final int BOOLEAN_ON_BELOW = 450;
    private static final int BOOLEAN_OFF_ABOVE = 570;
    private static final int PERCENT_FULL_AT_OR_BELOW = 391;

    private final Object firmware = new Object();
    private final boolean echo;
    private final double stepSeconds;
    private final String[] motorPort = new String[OUTPUTS];
    private final Output[] outputs = new Output[OUTPUTS];
    private final Input[] inputs = new Input[INPUTS];
    private final int ticksPerRevolution;
    private double seconds;
    private int lastOpcode = -1;
    private byte[] lastReply;

    /** One motor output. */
    private static final class Output {
        int power = RcxMotorDriver.POWER_STEPS - 1;
        boolean forward = true;
        int state = RcxPacket.FLOAT;
    }

    /** One sensor input. */
    private static final class Input {
        SensorSpec sensor;
        String countedMotor;
        int type = RcxPacket.TYPE_RAW;
        int mode = RcxPacket.MODE_RAW;
        int raw = RAW_OPEN;
        boolean bool;
        double rotationZero;
        double rotationDegrees;
    }

    /**
     * @param robot       the simulated robot
     * @param stepSeconds the world's physics step, seconds (for the timers)
     * @param echo        whether the tower echoes every packet (the serial tower does)
     */
    public RcxEmulator(SimMotors robot, double stepSeconds, boolean echo) {
        super("rcx", robot, FRAMING);
        if (!(stepSeconds > 0)) {
            throw new IllegalArgumentException("stepSeconds must be > 0, got " + stepSeconds);
        }
        this.stepSeconds = stepSeconds;
        this.echo = echo;
        RobotDescription d = robot.robot().description();
        for (int i = 0; i < OUTPUTS; i++) {
            String port = String.valueOf((char) ('A' + i));
            motorPort[i] = d.motorPorts().contains(port) ? port : null;
            outputs[i] = new Output();
        }
        for (int i = 0; i < INPUTS; i++) {
            inputs[i] = new Input();
        }
        for (SensorSpec s : d.sensors()) {
            int input = inputIndex(s.port());
            if (input >= 0) {
                inputs[input].sensor = s;
            }
        }
        ticksPerRevolution = d.drive().map(DifferentialDrive::encoderTicksPerRevolution).orElse(0);
        d.drive().ifPresent(drive -> {
            for (DifferentialDrive.Wheel w : List.of(drive.left(), drive.right())) {
                w.counter().ifPresent(c -> {
                    int input = inputIndex(c);
                    if (input >= 0) {
                        inputs[input].countedMotor = w.port();
                    }
                });
            }
        });
    }

    private static int inputIndex(String port) {
        String p = port.startsWith("S") ? port.substring(1) : port;
        return switch (p) {
            case "1" -> 0;
            case "2" -> 1;
            case "3" -> 2;
            default -> -1;
        };
    }

    /**
     * Binds an emulator to a robot of a simulation and steps it with the world.
     *
     * @param simulation the simulation (the robot must be one it emulates)
     * @param robotName  the robot
     * @return the emulator, not yet serving; closing it unbinds it
     */
    public static RcxEmulator bind(Simulation simulation, String robotName) {
        return bind(simulation, robotName, motors -> new RcxEmulator(motors, simulation.world().stepSeconds(), true));
    }

    /**
     * Binds an emulator behind a tower that does not echo (like the USB tower).
     *
     * @param simulation the simulation
     * @param robotName  the robot
     * @return the emulator, not yet serving
     */
    public static RcxEmulator bindWithoutEcho(Simulation simulation, String robotName) {
        return bind(simulation, robotName, motors -> new RcxEmulator(motors, simulation.world().stepSeconds(), false));
    }

    /** The serial IR tower's line: 2400 baud, 8 data bits, odd parity, 1 stop bit. */
    @Override
    protected LinkModel defaultLinkModel() {
        return LinkModel.serial(2400, 11);
    }

    /** Packets are delimited by their header and opcode: the opcode fixes how many data bytes follow. */
    static final Framing FRAMING = new Framing() {
        @Override
        public byte[] read(Reader in) throws IOException {
            byte[] head = in.readExactly(RcxPacket.HEADER_LENGTH + 2);
            if (head == null) {
                return null;
            }
            for (int i = 0; i < RcxPacket.HEADER_LENGTH; i++) {
                if (head[i] != RcxPacket.HEADER[i]) {
                    throw new MalformedFrameException("an RCX packet starts 55 FF 00, got " + RcxPacket.hex(head));
                }
            }
            int opcode = head[RcxPacket.HEADER_LENGTH] & 0xFF;
            int data = RcxPacket.requestDataLength(opcode);
            if (data < 0) {
                throw new MalformedFrameException(String.format("opcode %02X is not one the RCX emulator knows", opcode));
            }
            byte[] rest = in.readExactly(2 * data + 2);
            if (rest == null) {
                return null;
            }
            byte[] packet = new byte[head.length + rest.length];
            System.arraycopy(head, 0, packet, 0, head.length);
            System.arraycopy(rest, 0, packet, head.length, rest.length);
            return packet;
        }

        @Override
        public byte[] encode(byte[] reply) {
            return reply;
        }
    };

    // ---- I/O thread ----

    /** Echoes the packet (the tower hears itself), then answers it. */
    @Override
    protected byte[] handle(byte[] packet) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        if (echo) {
            out.writeBytes(packet);
        }
        byte[] reply = answer(packet);
        if (reply != null) {
            out.writeBytes(reply);
        }
        return out.size() == 0 ? null : out.toByteArray();
    }

    private byte[] answer(byte[] packet) {
        RcxPacket.Decoded request;
        try {
            request = RcxPacket.decode(packet);
        } catch (IllegalArgumentException e) {
            return null;
        }
        synchronized (firmware) {
            if (request.opcode() == lastOpcode && lastReply != null) {
                return lastReply;
            }
            byte[] data = run(request.opcode() & ~RcxPacket.TOGGLE, request.data());
            if (data == null) {
                return null;
            }
            lastOpcode = request.opcode();
            lastReply = RcxPacket.encode(RcxPacket.replyOpcode(request.opcode()), data);
            return lastReply;
        }
    }

    /** Runs a command; returns its reply's data, or null for one the brick does not answer. */
    private byte[] run(int opcode, byte[] d) {
        return switch (opcode) {
            case RcxPacket.ALIVE, RcxPacket.STOP_ALL_TASKS, RcxPacket.PLAY_SOUND, RcxPacket.PLAY_TONE -> new byte[0];
            case RcxPacket.GET_BATTERY -> u16(BATTERY_MILLIVOLTS);
            case RcxPacket.GET_VERSIONS -> new byte[]{0, 3, 0, 1, 0, 3, 0, 28};
            case RcxPacket.SET_MOTOR_POWER -> {
                int motors = d[0] & 0x07;
                int source = d[1] & 0xFF;
                int power = source == RcxPacket.SOURCE_CONSTANT ? Math.max(0, Math.min(7, d[2])) : 0;
                forEachMotor(motors, o -> o.power = power);
                yield new byte[0];
            }
            case RcxPacket.SET_MOTOR_DIRECTION -> {
                int code = d[0] & 0xFF;
                int how = code & 0xC0;
                forEachMotor(code & 0x07, o -> o.forward = how == RcxPacket.FORWARD || (how == RcxPacket.FLIP && !o.forward));
                yield new byte[0];
            }
            case RcxPacket.SET_MOTOR_ON_OFF -> {
                int code = d[0] & 0xFF;
                int state = code & 0xC0;
                forEachMotor(code & 0x07, o -> o.state = state == 0xC0 ? RcxPacket.ON : state);
                yield new byte[0];
            }
            case RcxPacket.SET_SENSOR_TYPE -> {
                int input = d[0] & 0xFF;
                if (input < INPUTS) {
                    inputs[input].type = d[1] & 0xFF;
                    clear(inputs[input]);
                }
                yield new byte[0];
            }
            case RcxPacket.SET_SENSOR_MODE -> {
                int input = d[0] & 0xFF;
                if (input < INPUTS) {
                    inputs[input].mode = d[1] & 0xFF;
                    clear(inputs[input]);
                }
                yield new byte[0];
            }
            case RcxPacket.GET_VALUE -> u16(value(d[0] & 0xFF, d[1] & 0xFF));
            default -> null;
        };
    }

    private void clear(Input in) {
        in.rotationZero = in.rotationDegrees;
        in.bool = false;
    }

    private void forEachMotor(int motors, java.util.function.Consumer<Output> action) {
        for (int i = 0; i < OUTPUTS; i++) {
            if ((motors & 1 << i) != 0) {
                action.accept(outputs[i]);
            }
        }
    }

    /** Get value: what a source gives, or 0 for one not emulated. */
    private int value(int source, int argument) {
        if (source == RcxPacket.SOURCE_MOTOR_STATE) {
            if (argument >= OUTPUTS) {
                return 0;
            }
            Output o = outputs[argument];
            return o.power | (o.forward ? 0 : 0x08) | (o.state == RcxPacket.ON ? 0x80 : o.state == RcxPacket.OFF ? 0x40 : 0);
        }
        if (source == RcxPacket.SOURCE_TIMER) {
            return (int) (seconds * 100) & 0x7FFF;
        }
        if (argument >= INPUTS) {
            return 0;
        }
        Input in = inputs[argument];
        return switch (source) {
            case RcxPacket.SOURCE_SENSOR_VALUE -> sensorValue(in);
            case RcxPacket.SOURCE_SENSOR_RAW -> in.raw;
            case RcxPacket.SOURCE_SENSOR_BOOLEAN -> in.bool ? 1 : 0;
            case RcxPacket.SOURCE_SENSOR_TYPE -> in.type;
            case RcxPacket.SOURCE_SENSOR_MODE -> in.mode;
            default -> 0;
        };
    }

    /** A sensor's value in its mode, as the firmware computes it from the raw reading. */
    private int sensorValue(Input in) {
        return switch (in.mode & 0xE0) {
            case RcxPacket.MODE_BOOLEAN -> in.bool ? 1 : 0;
            case RcxPacket.MODE_PERCENT -> in.raw <= PERCENT_FULL_AT_OR_BELOW ? 100 : (RAW_OPEN - in.raw) * 25 / 156;
            case RcxPacket.MODE_ANGLE -> in.type == RcxPacket.TYPE_ROTATION ? rotationCount(in) : 0;
            default -> in.raw;
        };
    }

    private int rotationCount(Input in) {
        return (int) Math.floor((in.rotationDegrees - in.rotationZero) * ticksPerRevolution / 360.0 + 0.5);
    }

    private static byte[] u16(int value) {
        return new byte[]{(byte) value, (byte) (value >> 8)};
    }

    // ---- simulation thread ----

    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            seconds += stepSeconds;
            for (int i = 0; i < OUTPUTS; i++) {
                if (motorPort[i] == null) {
                    continue;
                }
                Output o = outputs[i];
                double speed = o.state == RcxPacket.ON ? RcxMotorDriver.speedAt(o.power) : 0;
                robot.command(motorPort[i], o.forward ? speed : -speed);
            }
            for (Input in : inputs) {
                in.raw = raw(robot, in);
                if (in.raw < BOOLEAN_ON_BELOW) {
                    in.bool = true;
                } else if (in.raw > BOOLEAN_OFF_ABOVE) {
                    in.bool = false;
                }
                if (in.countedMotor != null && ticksPerRevolution > 0) {
                    in.rotationDegrees = robot.degrees(in.countedMotor);
                }
            }
        }
    }

    /** The raw reading of an input: what its sensor gives, 1023 for nothing plugged in. */
    private static int raw(SimMotors robot, Input in) {
        SensorSpec s = in.sensor;
        if (s == null || (in.type != RcxPacket.TYPE_TOUCH && in.type != RcxPacket.TYPE_LIGHT && in.type != RcxPacket.TYPE_RAW)) {
            return RAW_OPEN;
        }
        if (s.type() == SensorType.TOUCH) {
            return robot.siValue(s.name()) >= 0.5 ? RAW_PRESSED : RAW_OPEN;
        }
        if (s.type() == SensorType.LIGHT) {
            double percent = Math.max(0, Math.min(100, robot.siValue(s.name()) * 100));
            return (int) Math.round(RAW_OPEN - percent * 156 / 25);
        }
        return RAW_OPEN;
    }

    @Override
    protected void halt(SimMotors robot) {
        synchronized (firmware) {
            for (int i = 0; i < OUTPUTS; i++) {
                outputs[i].state = RcxPacket.FLOAT;
                if (motorPort[i] != null) {
                    robot.command(motorPort[i], 0);
                }
            }
        }
    }

    /**
     * @param port a motor port, A..C
     * @return whether that output floats (no power, no brake)
     */
    public boolean floating(String port) {
        synchronized (firmware) {
            return outputs[port.charAt(0) - 'A'].state == RcxPacket.FLOAT;
        }
    }
}
