package io.robomw.sim.emulator.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.api.SensorType;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.nxt.NxtStatus;
import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;
import io.robomw.sim.emulator.LinkModel;

import java.util.Arrays;

/**
 * A virtual LEGO Mindstorms NXT: answers LCP direct commands as the firmware does
 * ({@code c_cmd.c}: reply layouts, status 0xC0 with zero padding for a bad port, 0xBE for an
 * unknown opcode, the {@code valid} flag cleared by SETINPUTMODE until the next sensor update,
 * I²C transactions pending (0x20) until the next update, 0xE0 on a port that is not set up for
 * I²C), with its motors and sensors bound to a robot in a simulated world.
 *
 * <p>Motors follow the firmware's output module ({@link NxtOutputs}): power P (regulated) turns at
 * P % of {@link NxtTelegram#DEGREES_PER_SECOND_AT_FULL_POWER}; tacho limits add up to a running
 * target that only UPDATE_RESET_COUNT (0x21) zeroes, and a motor that reaches it coasts; a
 * synchronised pair keeps its block tacho counts together. Counters: tacho count (since
 * UPDATE_RESET_COUNT), block tacho count and rotation count (since their RESETMOTORPOSITION).
 * Inputs: the description's sensor on S1..S4, encoded for the type the driver set: switch (raw 183
 * pressed, 1023 released), light (normalized = brightness × 1023), colour (the colour number),
 * ultrasonic over I²C with its identity and measurement registers ({@link NxtUltrasonic}:
 * "V1.0", "LEGO", "Sonar"; centimetres, 255 for nothing in range).
 */
public final class NxtEmulator extends BrickEmulator {

    private static final int OUTPUTS = NxtOutputs.COUNT;
    private static final int INPUTS = 4;
    private static final int BATTERY_MILLIVOLTS = 8123;
    private static final long SLEEP_LIMIT_MILLIS = 600_000;

    private final Object firmware = new Object();
    private final NxtOutputs outputs;
    private final Input[] inputs = new Input[INPUTS];
    private final double stepSeconds;
    private final boolean resetCountCommand;
    private final java.util.Map<Integer, java.util.concurrent.atomic.AtomicLong> served = new java.util.concurrent.ConcurrentHashMap<>();

    /** One sensor input's firmware state. */
    private static final class Input {
        final SensorSpec sensor;
        int type;
        int mode;
        boolean valid;
        double si;
        int pendingRx = -1;
        int pendingRegister;
        int bytesReady;
        final NxtUltrasonic ultrasonic = new NxtUltrasonic();
        final byte[] lsData = new byte[16];

        Input(SensorSpec sensor) {
            this.sensor = sensor;
        }
    }

    private volatile int refuseWith;

    /**
     * An NXT with firmware 1.29 or later (which has UPDATE_RESET_COUNT).
     *
     * @param robot       the simulated robot whose motors and sensors it drives
     * @param stepSeconds the world's physics step, seconds
     */
    public NxtEmulator(SimMotors robot, double stepSeconds) {
        this(robot, stepSeconds, true);
    }

    /**
     * @param robot             the simulated robot whose motors and sensors it drives
     * @param stepSeconds       the world's physics step, seconds
     * @param resetCountCommand whether the firmware knows UPDATE_RESET_COUNT (0x21; LEGO 1.29 and
     *                          later); without it, as on earlier firmware, it answers 0xBE
     */
    public NxtEmulator(SimMotors robot, double stepSeconds, boolean resetCountCommand) {
        super("nxt", robot, NxtTelegram.MAX_LENGTH);
        if (!(stepSeconds > 0)) {
            throw new IllegalArgumentException("stepSeconds must be > 0, got " + stepSeconds);
        }
        this.stepSeconds = stepSeconds;
        this.resetCountCommand = resetCountCommand;
        var d = robot.robot().description();
        boolean[] connected = new boolean[OUTPUTS];
        for (int i = 0; i < OUTPUTS; i++) {
            connected[i] = d.motorPorts().contains(String.valueOf((char) ('A' + i)));
        }
        outputs = new NxtOutputs(connected);
        for (int i = 0; i < INPUTS; i++) {
            String port = "S" + (i + 1);
            String bare = String.valueOf(i + 1);
            inputs[i] = new Input(d.sensors().stream().filter(s -> s.port().equals(port) || s.port().equals(bare))
                    .findFirst().orElse(null));
        }
    }

    /**
     * Binds an emulator to a robot of a simulation and steps it with the world.
     *
     * @param simulation the simulation (the robot must be one it emulates, see {@code Simulation.load(world, names)})
     * @param robotName  the robot
     * @return the emulator, not yet serving: call {@code startOnPseudoTerminal()} or {@code startOnTcp(...)};
     *         closing it also unbinds it from the simulation
     */
    public static NxtEmulator bind(Simulation simulation, String robotName) {
        return bind(simulation, robotName, motors -> new NxtEmulator(motors, simulation.world().stepSeconds()));
    }

    /**
     * Binds an emulator of firmware older than 1.29, which has no UPDATE_RESET_COUNT.
     *
     * @param simulation the simulation
     * @param robotName  the robot
     * @return the emulator, not yet serving
     */
    public static NxtEmulator bindLegacyFirmware(Simulation simulation, String robotName) {
        return bind(simulation, robotName, motors -> new NxtEmulator(motors, simulation.world().stepSeconds(), false));
    }

    /**
     * @param opcode a direct command's opcode
     * @param port   the port its first payload byte names (an output or input)
     * @return how many such telegrams the emulator has answered
     */
    public long telegrams(int opcode, int port) {
        java.util.concurrent.atomic.AtomicLong n = served.get(opcode << 8 | port);
        return n == null ? 0 : n.get();
    }

    /** An NXT is usually reached over Bluetooth: {@link LinkModel#BLUETOOTH_SPP}. */
    @Override
    protected LinkModel defaultLinkModel() {
        return LinkModel.BLUETOOTH_SPP;
    }

    // ---- simulation thread ----

    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            double[] degrees = new double[OUTPUTS];
            for (int i = 0; i < OUTPUTS; i++) {
                NxtOutputs.Output o = outputs.get(i);
                degrees[i] = o.connected ? robot.degrees(o.port) : 0;
            }
            double[] speeds = outputs.step(degrees, stepSeconds);
            for (int i = 0; i < OUTPUTS; i++) {
                NxtOutputs.Output o = outputs.get(i);
                if (o.connected) {
                    robot.command(o.port, speeds[i]);
                }
            }
            for (Input in : inputs) {
                if (in.type == NxtTelegram.TYPE_NO_SENSOR) {
                    continue;
                }
                in.valid = true;
                in.si = in.sensor == null ? 0 : robot.siValue(in.sensor.name());
                if (in.pendingRx >= 0) {
                    Arrays.fill(in.lsData, (byte) 0);
                    byte[] answer = in.ultrasonic.read(in.pendingRegister, in.pendingRx, in.si);
                    System.arraycopy(answer, 0, in.lsData, 0, answer.length);
                    in.bytesReady = in.pendingRx;
                    in.pendingRx = -1;
                }
            }
        }
    }

    @Override
    protected void halt(SimMotors robot) {
        synchronized (firmware) {
            outputs.halt();
            for (int i = 0; i < OUTPUTS; i++) {
                NxtOutputs.Output o = outputs.get(i);
                if (o.connected) {
                    robot.command(o.port, 0);
                }
            }
        }
    }

    // ---- I/O thread ----

    /**
     * A faulty brick, for tests of what users see then: from now on every telegram that wants a
     * reply is answered with this status and nothing is done (as a brick whose firmware refuses
     * everything would); 0 makes it behave again.
     *
     * @param status an NXT status byte ({@link NxtStatus}), or 0
     */
    public void refuseEverythingWith(int status) {
        refuseWith = status;
    }

    @Override
    protected byte[] handle(byte[] frame) {
        if (frame.length < 2) {
            throw new IllegalArgumentException("a telegram needs a type and an opcode, got " + frame.length + " byte(s)");
        }
        int type = frame[0] & 0xFF;
        int op = frame[1] & 0xFF;
        served.computeIfAbsent(op << 8 | (frame.length > 2 ? frame[2] & 0xFF : 0xFF), k -> new java.util.concurrent.atomic.AtomicLong()).incrementAndGet();
        boolean wantsReply = (type & 0x80) == 0;
        int refusal = refuseWith;
        if (refusal != 0) {
            return wantsReply ? status(op, refusal) : null;
        }
        byte[] reply;
        if ((type & 0x7F) == NxtTelegram.SYSTEM) {
            reply = system(op);
        } else if ((type & 0x7F) == NxtTelegram.DIRECT) {
            synchronized (firmware) {
                reply = direct(op, frame);
            }
        } else {
            reply = status(op, NxtStatus.UNKNOWN_COMMAND);
        }
        return wantsReply ? reply : null;
    }

    private byte[] system(int op) {
        if (op == 0x88) {
            return new byte[]{NxtTelegram.REPLY, (byte) op, 0, 0x7C, 0x01, 0x1C, 0x01};
        }
        return status(op, NxtStatus.UNKNOWN_COMMAND);
    }

    private byte[] direct(int op, byte[] t) {
        return switch (op) {
            case NxtTelegram.PLAYTONE -> t.length < 6 ? status(op, NxtStatus.INSANE_PACKET) : status(op, NxtStatus.SUCCESS);
            case NxtTelegram.SETOUTPUTSTATE -> setOutputState(t);
            case NxtTelegram.SETINPUTMODE -> setInputMode(t);
            case NxtTelegram.GETOUTPUTSTATE -> getOutputState(t);
            case NxtTelegram.GETINPUTVALUES -> getInputValues(t);
            case NxtTelegram.RESETINPUTSCALEDVALUE -> inputPort(t) < 0 ? status(op, NxtStatus.OUT_OF_RANGE) : status(op, NxtStatus.SUCCESS);
            case NxtTelegram.RESETMOTORPOSITION -> resetMotorPosition(t);
            case NxtTelegram.UPDATE_RESET_COUNT -> updateResetCount(t);
            case NxtTelegram.GETBATTERYLEVEL -> {
                byte[] r = sized(op, NxtTelegram.GETBATTERYLEVEL_REPLY, NxtStatus.SUCCESS);
                LittleEndian.putU16(r, 3, BATTERY_MILLIVOLTS);
                yield r;
            }
            case NxtTelegram.STOPSOUNDPLAYBACK, NxtTelegram.MESSAGEWRITE -> status(op, NxtStatus.SUCCESS);
            case NxtTelegram.KEEPALIVE -> {
                byte[] r = sized(op, NxtTelegram.KEEPALIVE_REPLY, NxtStatus.SUCCESS);
                LittleEndian.putU32(r, 3, SLEEP_LIMIT_MILLIS);
                yield r;
            }
            case NxtTelegram.LSWRITE -> lsWrite(t);
            case NxtTelegram.LSGETSTATUS -> lsGetStatus(t);
            case NxtTelegram.LSREAD -> lsRead(t);
            case NxtTelegram.GETCURRENTPROGRAMNAME -> sized(op, 23, NxtStatus.NO_ACTIVE_PROGRAM);
            default -> status(op, NxtStatus.UNKNOWN_COMMAND);
        };
    }

    private byte[] setOutputState(byte[] t) {
        int op = NxtTelegram.SETOUTPUTSTATE;
        if (t.length < 12) {
            return status(op, NxtStatus.INSANE_PACKET);
        }
        int port = t[2] & 0xFF;
        if (port >= OUTPUTS && port != NxtTelegram.ALL_OUTPUTS) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        for (int i = 0; i < OUTPUTS; i++) {
            if (port == NxtTelegram.ALL_OUTPUTS || port == i) {
                outputs.setOutputState(i, Math.max(-100, Math.min(100, t[3])), t[4] & 0xFF, t[5] & 0xFF,
                        Math.max(-100, Math.min(100, t[6])), t[7] & 0xFF, LittleEndian.u32(t, 8));
            }
        }
        return status(op, NxtStatus.SUCCESS);
    }

    private byte[] getOutputState(byte[] t) {
        int op = NxtTelegram.GETOUTPUTSTATE;
        if (t.length < 3 || (t[2] & 0xFF) >= OUTPUTS) {
            return sized(op, NxtTelegram.GETOUTPUTSTATE_REPLY, t.length < 3 ? NxtStatus.INSANE_PACKET : NxtStatus.OUT_OF_RANGE);
        }
        NxtOutputs.Output o = outputs.get(t[2] & 0xFF);
        byte[] r = sized(op, NxtTelegram.GETOUTPUTSTATE_REPLY, NxtStatus.SUCCESS);
        r[3] = t[2];
        r[4] = (byte) o.power;
        r[5] = (byte) o.mode;
        r[6] = (byte) o.regulationMode;
        r[7] = (byte) o.turnRatio;
        r[8] = (byte) o.runState;
        LittleEndian.putU32(r, 9, o.tachoLimit);
        LittleEndian.putU32(r, 13, o.count());
        LittleEndian.putU32(r, 17, Math.round(o.blockCount()));
        LittleEndian.putU32(r, 21, Math.round(o.rotationCount()));
        return r;
    }

    private byte[] resetMotorPosition(byte[] t) {
        int op = NxtTelegram.RESETMOTORPOSITION;
        if (t.length < 4) {
            return status(op, NxtStatus.INSANE_PACKET);
        }
        int port = t[2] & 0xFF;
        if (port >= OUTPUTS) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        outputs.resetPosition(port, t[3] != 0);
        return status(op, NxtStatus.SUCCESS);
    }

    private byte[] updateResetCount(byte[] t) {
        int op = NxtTelegram.UPDATE_RESET_COUNT;
        if (!resetCountCommand) {
            return status(op, NxtStatus.UNKNOWN_COMMAND);
        }
        if (t.length < 3) {
            return status(op, NxtStatus.INSANE_PACKET);
        }
        int port = t[2] & 0xFF;
        if (port >= OUTPUTS) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        outputs.resetCount(port);
        return status(op, NxtStatus.SUCCESS);
    }

    private int inputPort(byte[] t) {
        return t.length < 3 || (t[2] & 0xFF) >= INPUTS ? -1 : t[2] & 0xFF;
    }

    private byte[] setInputMode(byte[] t) {
        int op = NxtTelegram.SETINPUTMODE;
        if (t.length < 5) {
            return status(op, NxtStatus.INSANE_PACKET);
        }
        int port = inputPort(t);
        if (port < 0) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        Input in = inputs[port];
        in.type = t[3] & 0xFF;
        in.mode = t[4] & 0xFF;
        in.valid = false;
        in.pendingRx = -1;
        in.bytesReady = 0;
        return status(op, NxtStatus.SUCCESS);
    }

    private byte[] getInputValues(byte[] t) {
        int op = NxtTelegram.GETINPUTVALUES;
        int port = inputPort(t);
        if (port < 0) {
            return sized(op, NxtTelegram.GETINPUTVALUES_REPLY, t.length < 3 ? NxtStatus.INSANE_PACKET : NxtStatus.OUT_OF_RANGE);
        }
        Input in = inputs[port];
        int raw = 1023;
        int normalized = 1023;
        int scaled = 0;
        switch (in.type) {
            case NxtTelegram.TYPE_SWITCH -> {
                boolean pressed = in.sensor != null && in.si >= 0.5;
                raw = pressed ? 183 : 1023;
                normalized = raw;
                scaled = (in.mode & 0xE0) == NxtTelegram.MODE_BOOLEAN ? (pressed ? 1 : 0) : raw;
            }
            case NxtTelegram.TYPE_LIGHT_ACTIVE, NxtTelegram.TYPE_LIGHT_INACTIVE, NxtTelegram.TYPE_SOUND_DB -> {
                normalized = (int) Math.max(0, Math.min(1023, Math.round(in.si * 1023)));
                raw = 1023 - normalized;
                scaled = (in.mode & 0xE0) == NxtTelegram.MODE_PCTFULLSCALE ? normalized * 100 / 1023 : normalized;
            }
            case NxtTelegram.TYPE_COLORFULL -> {
                raw = 0;
                normalized = 0;
                scaled = (int) Math.round(in.si);
            }
            default -> {
                raw = 0;
                normalized = 0;
            }
        }
        byte[] r = sized(op, NxtTelegram.GETINPUTVALUES_REPLY, NxtStatus.SUCCESS);
        r[3] = (byte) port;
        r[4] = (byte) (in.valid ? 1 : 0);
        r[5] = 0;
        r[6] = (byte) in.type;
        r[7] = (byte) in.mode;
        LittleEndian.putU16(r, 8, raw);
        LittleEndian.putU16(r, 10, normalized);
        LittleEndian.putU16(r, 12, scaled);
        LittleEndian.putU16(r, 14, normalized);
        return r;
    }

    private boolean lowSpeedReady(Input in) {
        return (in.type == 0x0A || in.type == NxtTelegram.TYPE_LOWSPEED_9V) && in.valid;
    }

    private byte[] lsWrite(byte[] t) {
        int op = NxtTelegram.LSWRITE;
        if (t.length < 5 || t.length < 5 + (t[3] & 0xFF)) {
            return status(op, NxtStatus.INSANE_PACKET);
        }
        int port = inputPort(t);
        if (port < 0) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        Input in = inputs[port];
        if (!lowSpeedReady(in)) {
            return status(op, NxtStatus.CHANNEL_NOT_READY);
        }
        int txLength = t[3] & 0xFF;
        int rxLength = t[4] & 0xFF;
        if (txLength > 16 || rxLength > 16) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        boolean sonar = in.sensor != null && in.sensor.type() == SensorType.SONAR
                && txLength >= 2 && (t[5] & 0xFF) == NxtTelegram.ULTRASONIC_ADDRESS;
        if (!sonar) {
            // Nothing answers at that address: the transaction ends with no data.
            in.pendingRx = -1;
            Arrays.fill(in.lsData, (byte) 0);
            in.bytesReady = rxLength;
            return status(op, NxtStatus.SUCCESS);
        }
        int register = t[6] & 0xFF;
        if (txLength > 2) {
            in.ultrasonic.write(register, Arrays.copyOfRange(t, 7, 5 + txLength));
        }
        // The sensor answers in the next I²C cycle: pending until the next sensor update.
        in.pendingRegister = register;
        in.pendingRx = rxLength;
        in.bytesReady = 0;
        return status(op, NxtStatus.SUCCESS);
    }

    private byte[] lsGetStatus(byte[] t) {
        int op = NxtTelegram.LSGETSTATUS;
        int port = inputPort(t);
        if (port < 0) {
            return sized(op, NxtTelegram.LSGETSTATUS_REPLY, t.length < 3 ? NxtStatus.INSANE_PACKET : NxtStatus.OUT_OF_RANGE);
        }
        Input in = inputs[port];
        if (!lowSpeedReady(in)) {
            return sized(op, NxtTelegram.LSGETSTATUS_REPLY, NxtStatus.CHANNEL_NOT_READY);
        }
        if (in.pendingRx >= 0) {
            return sized(op, NxtTelegram.LSGETSTATUS_REPLY, NxtStatus.PENDING);
        }
        byte[] r = sized(op, NxtTelegram.LSGETSTATUS_REPLY, NxtStatus.SUCCESS);
        r[3] = (byte) in.bytesReady;
        return r;
    }

    private byte[] lsRead(byte[] t) {
        int op = NxtTelegram.LSREAD;
        int port = inputPort(t);
        if (port < 0) {
            return sized(op, NxtTelegram.LSREAD_REPLY, t.length < 3 ? NxtStatus.INSANE_PACKET : NxtStatus.OUT_OF_RANGE);
        }
        Input in = inputs[port];
        if (in.pendingRx >= 0) {
            return sized(op, NxtTelegram.LSREAD_REPLY, NxtStatus.PENDING);
        }
        byte[] r = sized(op, NxtTelegram.LSREAD_REPLY, NxtStatus.SUCCESS);
        r[3] = (byte) in.bytesReady;
        System.arraycopy(in.lsData, 0, r, 4, Math.min(16, in.bytesReady));
        in.bytesReady = 0;
        return r;
    }

    private static byte[] status(int op, int status) {
        return new byte[]{NxtTelegram.REPLY, (byte) op, (byte) status};
    }

    /** A reply of the documented length; on errors the firmware pads it with zeros. */
    private static byte[] sized(int op, int length, int status) {
        byte[] r = new byte[length];
        r[0] = NxtTelegram.REPLY;
        r[1] = (byte) op;
        r[2] = (byte) status;
        return r;
    }
}
