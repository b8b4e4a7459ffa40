package io.robomw.sim.emulator.ev3;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.api.SensorType;
import io.robomw.api.spi.SensorChannel;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.ev3.Ev3CodeReader;
import io.robomw.platform.ev3.Ev3Device;
import io.robomw.platform.ev3.Ev3Frame;
import io.robomw.platform.ev3.Ev3MotorDriver;
import io.robomw.platform.ev3.Ev3Opcode;
import io.robomw.platform.ev3.Ev3Ports;
import io.robomw.platform.ev3.Ev3Reply;
import io.robomw.platform.ev3.Ev3SensorPlatform;
import io.robomw.platform.ev3.Ev3Subcode;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.LinkModel;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.util.Arrays;
import java.util.Set;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A virtual LEGO Mindstorms EV3 running the standard firmware: it answers direct commands as
 * {@code c_com.c} and the byte-code virtual machine do, with its motors and sensors bound to a
 * robot in a simulated world.
 *
 * <h2>Commands and replies</h2>
 * The header is checked as {@code cComDirectCommand} does: no byte codes, or more than 1021 global
 * bytes, gets the bare error reply {@code 03 00 cc cc 04}. The byte codes then run in order
 * (constants in every LC form, results into GV or LV variables); the reply is
 * {@code DIRECT_REPLY} with exactly {@code globals} bytes, or, when the virtual machine fails (an
 * unknown opcode or sub-code, a bad layer or port, a malformed parameter), {@code DIRECT_REPLY_ERROR}
 * with the globals as far as they were written. A command of type 0x80 runs but gets no reply.
 * System commands are not emulated: they get {@code SYSTEM_REPLY_ERROR} with status 0x0A
 * (unknown error).
 *
 * <h2>Motors A..D</h2>
 * Regulated speed S turns a motor at S % of {@link Ev3MotorDriver#DEGREES_PER_SECOND_AT_FULL_SPEED}
 * (the driver's constant). opOUTPUT_STEP_SPEED runs until the tacho has moved STEP1 + STEP2 + STEP3
 * degrees (ramping up over STEP1 and down over STEP3), slowing in its last simulation step so it
 * lands on the target, then stops; opOUTPUT_READY holds its command until then.
 * opOUTPUT_SPEED/POWER + opOUTPUT_START run; opOUTPUT_STOP stops. opOUTPUT_GET_COUNT is the
 * simulated encoder less the opOUTPUT_CLR_COUNT offset. Outputs with no motor in the description
 * accept commands and count nothing, as an empty port does.
 *
 * <h2>Sensors S1..S4</h2>
 * The plugged-in device is the one the driver would ask for the description's sensor on that port
 * ({@link Ev3SensorPlatform#setup}); its value is the sensor's true value ({@link SimMotors#siValue})
 * as the EV3 reports it for the asked mode: touch 1/0 (bumps: presses counted), colour reflected or
 * ambient light % = brightness × 100 and colour number, ultrasonic cm (0.1 cm steps, 255 beyond
 * range) or inch, gyro degrees and degrees per second (clockwise positive, as the sensor mounted
 * upright reports), infra-red proximity % = distance / 0.70 m × 100 (0..100). READY_RAW and
 * READY_PCT follow from {@code typedata.rcf}'s ranges. A read that asks for another device type than
 * the one plugged in, or of an empty port, gives the firmware's "no value" (NaN, 0x80000000, -128).
 * Motors read as sensors (inputs 16..19) give degrees, rotations or speed %.
 *
 * <h2>Threads</h2>
 * {@link #handle} runs on the I/O thread, {@link #step} on the simulation thread; both hold the one
 * firmware lock. opOUTPUT_READY waits on that lock's monitor, so the simulation goes on meanwhile.
 */
public final class Ev3Emulator extends BrickEmulator {

    private static final Logger LOG = LoggerFactory.getLogger(Ev3Emulator.class);

    /** What opUI_READ GET_VBATT reports, volts. */
    public static final float BATTERY_VOLTS = 7.8f;
    /** System-command status: unknown error. */
    private static final int SYSTEM_UNKNOWN_ERROR = 0x0A;
    /** Infra-red proximity reads 100 % at this distance, metres. */
    static final double INFRARED_FULL_SCALE_METRES = 0.70;
    /** The slowest a ramp runs, as a fraction of the step command's speed, so a ramp from 0 gets going. */
    private static final double MIN_RAMP = 0.1;
    private static final double METRES_PER_INCH = 0.0254;

    private final Object firmware = new Object();
    private final Output[] outputs = new Output[Ev3Ports.OUTPUTS.size()];
    private final Input[] inputs = new Input[Ev3Ports.INPUTS];
    private final double stepSeconds;
    private final AtomicLong vmFailures = new AtomicLong();
    private final AtomicLong tones = new AtomicLong();
    private boolean shutDown;

    /** What a motor output is doing. */
    private enum Run {
        IDLE,
        RUNNING,
        STEPPING
    }

    /** One motor output's firmware state. */
    private static final class Output {
        final String port;
        final boolean connected;
        final boolean wheel;
        Run run = Run.IDLE;
        /** Whether the last opOUTPUT_STOP braked (the motor holds) rather than let it coast. */
        boolean braked;
        /** Whether the running step command brakes at its end. */
        boolean stepBrake;
        int speed;
        double degrees;
        double countOffset;
        double commanded;
        int stepSpeed;
        double stepStart;
        double step1;
        double step2;
        double step3;

        Output(String port, boolean connected, boolean wheel) {
            this.port = port;
            this.connected = connected;
            this.wheel = wheel;
        }

        double count() {
            return degrees - countOffset;
        }
    }

    /** One sensor input's firmware state. */
    private static final class Input {
        final SensorSpec sensor;
        final int plugged;
        int mode;
        double si;
        boolean pressed;
        int bumps;
        double rate;

        Input(SensorSpec sensor, int plugged) {
            this.sensor = sensor;
            this.plugged = plugged;
        }
    }

    /**
     * @param robot       the simulated robot whose motors and sensors it drives
     * @param stepSeconds the world's physics step, seconds (step commands slow in their last step to land on target)
     */
    public Ev3Emulator(SimMotors robot, double stepSeconds) {
        super("ev3", robot, Ev3Frame.MAX_COMMAND_LENGTH);
        if (!(stepSeconds > 0)) {
            throw new IllegalArgumentException("stepSeconds must be > 0, got " + stepSeconds);
        }
        this.stepSeconds = stepSeconds;
        var d = robot.robot().description();
        Set<String> wheels = d.drive().map(dd -> Set.of(dd.left().port(), dd.right().port())).orElse(Set.of());
        for (int i = 0; i < outputs.length; i++) {
            String port = Ev3Ports.OUTPUTS.get(i);
            outputs[i] = new Output(port, d.motorPorts().contains(port), wheels.contains(port));
        }
        for (int i = 0; i < inputs.length; i++) {
            inputs[i] = new Input(null, Ev3Device.NONE.type());
        }
        for (SensorSpec s : d.sensors()) {
            int no;
            try {
                no = Ev3Ports.inputNumber(s.port());
            } catch (IllegalArgumentException e) {
                continue;
            }
            int plugged;
            try {
                plugged = Ev3SensorPlatform.setup(new SensorChannel(s.name(), s.type(), s.port(), s.options())).type();
            } catch (IllegalArgumentException e) {
                plugged = Ev3Device.NONE.type();
            }
            inputs[no] = new Input(s, plugged);
        }
    }

    /**
     * Binds an emulator to a robot of a simulation and steps it with the world: the factory
     * {@code mw emulate ev3} uses.
     *
     * @param simulation the simulation (the robot should be one it emulates, see {@code Simulation.load(world, names)})
     * @param robotName  the robot
     * @return the emulator, not yet serving: call {@code startOnPseudoTerminal()} or {@code startOnTcp(...)};
     *         closing it also unbinds it from the simulation
     * @throws IllegalArgumentException if the world has no such robot
     */
    public static Ev3Emulator bind(Simulation simulation, String robotName) {
        return bind(simulation, robotName, motors -> new Ev3Emulator(motors, simulation.world().stepSeconds()));
    }

    /** @return direct commands answered with {@code DIRECT_REPLY_ERROR} because the virtual machine failed */
    public long vmFailures() {
        return vmFailures.get();
    }

    /**
     * @param port a motor port, A..D
     * @return whether that output is stopped and braking (holding its motor, drawing current);
     *         false when it runs or was stopped coasting
     */
    public boolean braking(String port) {
        synchronized (firmware) {
            Output o = outputs[Ev3Ports.outputNumber(port)];
            return o.run == Run.IDLE && o.braked;
        }
    }

    /** @return tones played (opSOUND TONE) */
    public long tonesPlayed() {
        return tones.get();
    }

    /** An EV3 is usually reached over Bluetooth: {@link LinkModel#BLUETOOTH_SPP}. */
    @Override
    protected LinkModel defaultLinkModel() {
        return LinkModel.BLUETOOTH_SPP;
    }

    // ---- simulation thread ----

    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            boolean finished = false;
            for (Output o : outputs) {
                if (!o.connected) {
                    continue;
                }
                o.degrees = robot.degrees(o.port);
                boolean stepping = o.run == Run.STEPPING;
                double speed = switch (o.run) {
                    case IDLE -> 0;
                    case RUNNING -> degreesPerSecond(o.speed);
                    case STEPPING -> stepSpeed(o);
                };
                finished |= stepping && o.run != Run.STEPPING;
                o.commanded = speed;
                robot.command(o.port, speed);
            }
            for (Input in : inputs) {
                if (in.sensor == null) {
                    continue;
                }
                double si = robot.siValue(in.sensor.name());
                in.rate = (si - in.si) / stepSeconds;
                in.si = si;
                boolean pressed = si >= 0.5;
                if (pressed && !in.pressed) {
                    in.bumps++;
                }
                in.pressed = pressed;
            }
            if (finished) {
                firmware.notifyAll();
            }
        }
    }

    private static double degreesPerSecond(int speedPercent) {
        return speedPercent / 100.0 * Ev3MotorDriver.DEGREES_PER_SECOND_AT_FULL_SPEED;
    }

    /**
     * The speed of a step command for the next world step. A wheel's new speed reaches the body one
     * step later than an actuator's (the world sets body velocities before its listeners run), so
     * for wheels the step already under way at the last speed counts as travelled.
     */
    private double stepSpeed(Output o) {
        double pending = o.wheel ? o.commanded * stepSeconds : 0;
        double progress = Math.abs(o.degrees + pending - o.stepStart);
        double total = o.step1 + o.step2 + o.step3;
        double left = total - progress;
        if (left <= 1e-9) {
            o.run = Run.IDLE;
            o.braked = o.stepBrake;
            return 0;
        }
        double factor = 1;
        if (o.step1 > 0 && progress < o.step1) {
            factor = Math.max(MIN_RAMP, progress / o.step1);
        }
        if (o.step3 > 0 && left < o.step3) {
            factor = Math.min(factor, Math.max(MIN_RAMP, left / o.step3));
        }
        double speed = Math.min(Math.abs(degreesPerSecond(o.stepSpeed)) * factor, left / stepSeconds);
        return Math.signum(o.stepSpeed) * speed;
    }

    @Override
    protected void halt(SimMotors robot) {
        synchronized (firmware) {
            for (Output o : outputs) {
                o.run = Run.IDLE;
                o.commanded = 0;
                if (o.connected) {
                    robot.command(o.port, 0);
                }
            }
            firmware.notifyAll();
        }
    }

    /** Stops serving; a command held by opOUTPUT_READY is released first. */
    @Override
    public void close() {
        synchronized (firmware) {
            shutDown = true;
            firmware.notifyAll();
        }
        super.close();
    }

    // ---- I/O thread ----

    @Override
    protected byte[] handle(byte[] body) {
        if (body.length < Ev3Frame.TYPE_FIELD_OFFSET - Ev3Frame.LENGTH_FIELD_SIZE + 1) {
            throw new IllegalArgumentException("an EV3 command starts with a message counter and a type, got " + body.length + " byte(s)");
        }
        byte[] frame = Ev3Frame.withLength(body);
        int counter = Ev3Frame.counter(frame);
        int type = Ev3Frame.type(frame);
        return switch (type) {
            case Ev3Frame.DIRECT_COMMAND_REPLY -> withoutLength(direct(frame, counter).encode());
            case Ev3Frame.DIRECT_COMMAND_NO_REPLY -> {
                direct(frame, counter);
                yield null;
            }
            case Ev3Frame.SYSTEM_COMMAND_REPLY -> systemError(frame, counter);
            case Ev3Frame.SYSTEM_COMMAND_NO_REPLY -> null;
            default -> throw new IllegalArgumentException(String.format("command type 0x%02X is none of the EV3's", type));
        };
    }

    private static byte[] withoutLength(byte[] frame) {
        return Arrays.copyOfRange(frame, Ev3Frame.LENGTH_FIELD_SIZE, frame.length);
    }

    private static byte[] systemError(byte[] frame, int counter) {
        byte[] reply = new byte[5];
        LittleEndian.putU16(reply, 0, counter);
        reply[2] = (byte) Ev3Frame.SYSTEM_REPLY_ERROR;
        reply[3] = frame.length > Ev3Frame.TYPE_FIELD_OFFSET + 1 ? frame[Ev3Frame.TYPE_FIELD_OFFSET + 1] : 0;
        reply[4] = (byte) SYSTEM_UNKNOWN_ERROR;
        return reply;
    }

    /** Checks the header as {@code cComDirectCommand} does, then runs the byte codes. */
    private Ev3Reply direct(byte[] frame, int counter) {
        if (frame.length <= Ev3Frame.CODE_OFFSET) {
            return Ev3Reply.error(counter, new byte[0]);
        }
        int vars = LittleEndian.u16(frame, Ev3Frame.VARS_FIELD_OFFSET);
        int globals = Ev3Frame.globalsOf(vars);
        if (globals > Ev3Frame.MAX_GLOBALS) {
            return Ev3Reply.error(counter, new byte[0]);
        }
        Ev3Vm vm = new Ev3Vm(Ev3CodeReader.ofCommand(frame), globals, Ev3Frame.localsOf(vars));
        synchronized (firmware) {
            try {
                while (vm.hasMore()) {
                    execute(vm);
                }
                return Ev3Reply.ok(counter, vm.globals());
            } catch (Ev3Vm.Failure e) {
                long n = vmFailures.incrementAndGet();
                LOG.debug("ev3 emulator for '{}': direct command #{} failed ({} so far): {}", robot().robot().name(), counter, n, e.getMessage());
                return Ev3Reply.error(counter, vm.globals());
            }
        }
    }

    private void execute(Ev3Vm vm) {
        int at = vm.position();
        int code = vm.opcode();
        Ev3Opcode op = Ev3Opcode.of(code).orElseThrow(() -> new Ev3Vm.Failure(Ev3Opcode.describe(code) + " at byte " + at + " is not an opcode this brick runs"));
        switch (op) {
            case NOP -> {
            }
            case OUTPUT_STOP -> {
                int nos = nos(vm);
                boolean brake = vm.data8() != 0;
                forEach(nos, o -> {
                    o.run = Run.IDLE;
                    o.braked = brake;
                });
            }
            case OUTPUT_POWER, OUTPUT_SPEED -> {
                int nos = nos(vm);
                int speed = percent(vm.data8());
                forEach(nos, o -> {
                    o.speed = speed;
                    if (o.run == Run.STEPPING) {
                        o.run = Run.RUNNING;
                    }
                });
            }
            case OUTPUT_START -> forEach(nos(vm), o -> o.run = Run.RUNNING);
            case OUTPUT_READ -> {
                Output o = outputs[outputNumber(vm)];
                vm.store8((int) Math.round(o.commanded / Ev3MotorDriver.DEGREES_PER_SECOND_AT_FULL_SPEED * 100));
                vm.store32((int) Math.round(o.count()));
            }
            case OUTPUT_TEST -> vm.store8(busy(nos(vm), Set.of(Run.RUNNING, Run.STEPPING)) ? 1 : 0);
            case OUTPUT_READY -> awaitSteps(nos(vm));
            case OUTPUT_STEP_SPEED -> {
                int nos = nos(vm);
                int speed = percent(vm.data8());
                int step1 = Math.abs(vm.data32());
                int step2 = Math.abs(vm.data32());
                int step3 = Math.abs(vm.data32());
                boolean brake = vm.data8() != 0;
                forEach(nos, o -> {
                    o.run = Run.STEPPING;
                    o.stepBrake = brake;
                    o.stepSpeed = speed;
                    o.stepStart = o.degrees;
                    o.step1 = step1;
                    o.step2 = step2;
                    o.step3 = step3;
                });
            }
            case OUTPUT_CLR_COUNT -> forEach(nos(vm), o -> o.countOffset = o.degrees);
            case OUTPUT_GET_COUNT -> vm.store32((int) Math.round(outputs[outputNumber(vm)].count()));
            case INPUT_DEVICE -> inputDevice(vm);
            case INPUT_READ -> {
                int no = inputNumber(vm);
                Reading r = read(no, vm.data8(), vm.data8());
                vm.store8(r.pct());
            }
            case INPUT_READSI -> {
                int no = inputNumber(vm);
                Reading r = read(no, vm.data8(), vm.data8());
                vm.storeF(r.si());
            }
            case UI_READ -> {
                int sub = vm.data8();
                if (Ev3Subcode.of(Ev3Opcode.UI_READ, sub).orElse(null) != Ev3Subcode.GET_VBATT) {
                    throw new Ev3Vm.Failure("opUI_READ sub-code " + sub + " is not emulated");
                }
                vm.storeF(BATTERY_VOLTS);
            }
            case SOUND -> {
                int sub = vm.data8();
                Ev3Subcode s = Ev3Subcode.of(Ev3Opcode.SOUND, sub).orElseThrow(() -> new Ev3Vm.Failure("opSOUND sub-code " + sub + " is not emulated"));
                if (s == Ev3Subcode.TONE) {
                    vm.data8();
                    vm.data16();
                    vm.data16();
                    tones.incrementAndGet();
                }
            }
        }
    }

    private static void layer(Ev3Vm vm) {
        int layer = vm.data8();
        if (layer != Ev3Ports.LAYER_MASTER) {
            throw new Ev3Vm.Failure("layer " + layer + ": this brick has no daisy-chained bricks");
        }
    }

    /** Reads LAYER and NOS. */
    private static int nos(Ev3Vm vm) {
        layer(vm);
        int nos = vm.data8() & 0xFF;
        if ((nos & ~0x0F) != 0) {
            throw new Ev3Vm.Failure(String.format("output bit field 0x%02X names ports beyond A..D", nos));
        }
        return nos;
    }

    /** Reads LAYER and NO, an output number. */
    private static int outputNumber(Ev3Vm vm) {
        layer(vm);
        int no = vm.data8();
        if (no < 0 || no >= Ev3Ports.OUTPUTS.size()) {
            throw new Ev3Vm.Failure("output port " + no + " does not exist (0..3 are A..D)");
        }
        return no;
    }

    /** Reads LAYER and NO, an input number. */
    private static int inputNumber(Ev3Vm vm) {
        layer(vm);
        int no = vm.data8();
        boolean sensor = no >= 0 && no < Ev3Ports.INPUTS;
        boolean motor = no >= Ev3Ports.FIRST_MOTOR_INPUT && no < Ev3Ports.FIRST_MOTOR_INPUT + Ev3Ports.OUTPUTS.size();
        if (!sensor && !motor) {
            throw new Ev3Vm.Failure("input port " + no + " does not exist (0..3 are S1..S4, 16..19 the motors A..D)");
        }
        return no;
    }

    private static int percent(int value) {
        return Math.max(-100, Math.min(100, value));
    }

    private void forEach(int nos, java.util.function.Consumer<Output> action) {
        for (int i = 0; i < outputs.length; i++) {
            if ((nos & 1 << i) != 0 && outputs[i].connected) {
                action.accept(outputs[i]);
            }
        }
    }

    private boolean busy(int nos, Set<Run> busyStates) {
        for (int i = 0; i < outputs.length; i++) {
            if ((nos & 1 << i) != 0 && outputs[i].connected && busyStates.contains(outputs[i].run)) {
                return true;
            }
        }
        return false;
    }

    /** opOUTPUT_READY: waits, releasing the firmware lock, until no output of nos is stepping. */
    private void awaitSteps(int nos) {
        while (!shutDown && busy(nos, Set.of(Run.STEPPING))) {
            try {
                firmware.wait(100);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new Ev3Vm.Failure("interrupted while waiting for the outputs to finish");
            }
        }
    }

    // ---- inputs ----

    private void inputDevice(Ev3Vm vm) {
        int sub = vm.data8();
        Ev3Subcode s = Ev3Subcode.of(Ev3Opcode.INPUT_DEVICE, sub)
                .orElseThrow(() -> new Ev3Vm.Failure("opINPUT_DEVICE sub-code " + sub + " is not emulated"));
        int no = inputNumber(vm);
        if (s == Ev3Subcode.GET_TYPEMODE) {
            vm.store8(plugged(no));
            vm.store8(no < Ev3Ports.INPUTS ? inputs[no].mode : 0);
            return;
        }
        Reading r = read(no, vm.data8(), vm.data8());
        int values = vm.data8();
        for (int i = 0; i < values; i++) {
            Reading v = i == 0 ? r : Reading.NONE;
            switch (s) {
                case READY_SI -> vm.storeF(v.si());
                case READY_RAW -> vm.store32(v.raw());
                default -> vm.store8(v.pct());
            }
        }
    }

    private int plugged(int no) {
        if (no < Ev3Ports.INPUTS) {
            return inputs[no].plugged;
        }
        return outputs[no - Ev3Ports.FIRST_MOTOR_INPUT].connected ? Ev3Device.LARGE_MOTOR.type() : Ev3Device.NONE.type();
    }

    /**
     * One reading in the three forms the firmware gives.
     *
     * @param si  SI value, NaN for none
     * @param raw raw value, {@link Ev3Reply#NAN_DATA32} for none
     * @param pct percent, {@link Ev3Reply#NAN_DATA8} for none
     */
    private record Reading(float si, int raw, int pct) {
        static final Reading NONE = new Reading(Float.NaN, Ev3Reply.NAN_DATA32, Ev3Reply.NAN_DATA8);
    }

    /**
     * Reads an input in the asked type and mode (0 and -1 keep the port's), as the plugged-in
     * device reports it; switches the port to that mode.
     */
    private Reading read(int no, int type, int mode) {
        int plugged = plugged(no);
        boolean motor = no >= Ev3Ports.FIRST_MOTOR_INPUT;
        int current = motor ? 0 : inputs[no].mode;
        int askedType = type == Ev3Device.KEEP_TYPE ? plugged : type;
        int askedMode = mode == Ev3Device.KEEP_MODE ? current : mode;
        boolean motorType = askedType == Ev3Device.LARGE_MOTOR.type() || askedType == Ev3Device.MEDIUM_MOTOR.type();
        boolean matches = motor ? plugged != Ev3Device.NONE.type() && motorType : askedType == plugged;
        if (!matches || plugged == Ev3Device.NONE.type()) {
            return Reading.NONE;
        }
        Ev3DeviceModes.Row row = Ev3DeviceModes.of(askedType, askedMode).orElse(null);
        if (row == null) {
            return Reading.NONE;
        }
        if (!motor) {
            inputs[no].mode = askedMode;
        }
        double value = motor ? motorValue(outputs[no - Ev3Ports.FIRST_MOTOR_INPUT], askedMode) : sensorValue(inputs[no], askedType, askedMode);
        if (Double.isNaN(value)) {
            return Reading.NONE;
        }
        long raw = row.rawOf(value);
        return new Reading((float) row.siOf(raw), (int) raw, (int) Math.max(-128, Math.min(127, row.pctOf(raw))));
    }

    private static double motorValue(Output o, int mode) {
        return switch (mode) {
            case 0 -> o.count();
            case 1 -> o.count() / 360;
            default -> o.commanded / Ev3MotorDriver.DEGREES_PER_SECOND_AT_FULL_SPEED * 100;
        };
    }

    /** The device's SI value from the simulated sensor's true value. */
    private static double sensorValue(Input in, int type, int mode) {
        double si = in.si;
        boolean colourSensor = in.sensor.type() == SensorType.COLOR;
        return switch (Ev3Device.of(type).orElse(Ev3Device.ERROR)) {
            case TOUCH -> mode == 0 ? (in.pressed ? 1 : 0) : in.bumps;
            case COLOR -> switch (mode) {
                case 0, 1 -> colourSensor ? 0 : clamp(si * 100, 0, 100);
                default -> colourSensor ? clamp(Math.round(si), 0, 7) : 0;
            };
            case ULTRASONIC -> switch (mode) {
                case 0 -> clamp(si * 100, 0, 255);
                case 1 -> clamp(si / METRES_PER_INCH, 0, 100);
                default -> 0;
            };
            case GYRO -> mode == 0 ? -Math.toDegrees(si) : -Math.toDegrees(in.rate);
            case INFRARED -> mode == 0 ? clamp(si / INFRARED_FULL_SCALE_METRES * 100, 0, 100) : 0;
            default -> Double.NaN;
        };
    }

    private static double clamp(double v, double min, double max) {
        return Math.max(min, Math.min(max, v));
    }
}
