package io.robomw.sim.emulator.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.config.description.SensorSpec;
import io.robomw.platform.nxt.NxtStatus;
import io.robomw.platform.nxt.NxtTelegram;
import io.robomw.sim.SimMotors;
import io.robomw.sim.Simulation;
import io.robomw.sim.emulator.BrickEmulator;

import java.util.Arrays;

/**
 * A virtual LEGO Mindstorms NXT: answers LCP direct commands as the firmware does
 * ({@code c_cmd.c}: reply layouts, status 0xC0 with zero padding for a bad port, 0xBE for an
 * unknown opcode, the {@code valid} flag cleared by SETINPUTMODE until the next sensor update,
 * I²C transactions pending (0x20) until the next update, 0xE0 on a port that is not set up for
 * I²C), with its motors and sensors bound to a robot in a simulated world.
 *
 * <p>Motors: power P (regulated) turns at P % of
 * {@link NxtTelegram#DEGREES_PER_SECOND_AT_FULL_POWER}; a tacho limit stops the motor when reached;
 * two motors in sync regulation with a turn ratio run at the firmware's ratio. Counters: tacho
 * count (since the command), block tacho count and rotation count (since their resets). Inputs:
 * the description's sensor on S1..S4, encoded for the type the driver set: switch (raw 183
 * pressed, 1023 released), light (normalized = brightness × 1023), colour (the colour number),
 * ultrasonic over I²C (centimetres, 255 for nothing in range).
 */
public final class NxtEmulator extends BrickEmulator {

    private static final int OUTPUTS = 3;
    private static final int INPUTS = 4;
    private static final int BATTERY_MILLIVOLTS = 8123;
    private static final long SLEEP_LIMIT_MILLIS = 600_000;

    private final Object firmware = new Object();
    private final Output[] outputs = new Output[OUTPUTS];
    private final Input[] inputs = new Input[INPUTS];

    /** One motor output's firmware state. */
    private static final class Output {
        final String port;
        final boolean connected;
        int power;
        int mode;
        int regulation;
        int turnRatio;
        int runState;
        long tachoLimit;
        double degrees;
        double tachoOffset;
        double blockOffset;
        double rotationOffset;
        double speed;

        Output(String port, boolean connected) {
            this.port = port;
            this.connected = connected;
        }
    }

    /** One sensor input's firmware state. */
    private static final class Input {
        final SensorSpec sensor;
        int type;
        int mode;
        boolean valid;
        double si;
        int pendingRx = -1;
        int bytesReady;
        final byte[] lsData = new byte[16];

        Input(SensorSpec sensor) {
            this.sensor = sensor;
        }
    }

    private volatile int refuseWith;

    /**
     * @param robot the simulated robot whose motors and sensors it drives
     */
    public NxtEmulator(SimMotors robot) {
        super("nxt", robot, NxtTelegram.MAX_LENGTH);
        var d = robot.robot().description();
        for (int i = 0; i < OUTPUTS; i++) {
            String port = String.valueOf((char) ('A' + i));
            outputs[i] = new Output(port, d.motorPorts().contains(port));
        }
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
        return bind(simulation, robotName, NxtEmulator::new);
    }

    // ---- simulation thread ----

    @Override
    protected void step(SimMotors robot) {
        synchronized (firmware) {
            for (Output o : outputs) {
                if (!o.connected) {
                    continue;
                }
                o.degrees = robot.degrees(o.port);
                boolean on = o.runState == NxtTelegram.RUN_RUNNING && (o.mode & NxtTelegram.MODE_MOTORON) != 0 && o.power != 0;
                if (on && o.tachoLimit > 0 && Math.abs(o.degrees - o.tachoOffset) >= o.tachoLimit) {
                    o.power = 0;
                    o.runState = NxtTelegram.RUN_IDLE;
                    on = false;
                }
                o.speed = on ? o.power / 100.0 * NxtTelegram.DEGREES_PER_SECOND_AT_FULL_POWER * syncFactor(o) : 0;
            }
            correctSyncedPair();
            for (Output o : outputs) {
                if (o.connected) {
                    robot.command(o.port, o.speed);
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
                    in.lsData[0] = (byte) Math.max(0, Math.min(255, Math.round(in.si * 100)));
                    in.bytesReady = in.pendingRx;
                    in.pendingRx = -1;
                }
            }
        }
    }

    @Override
    protected void halt(SimMotors robot) {
        synchronized (firmware) {
            for (Output o : outputs) {
                o.power = 0;
                o.runState = NxtTelegram.RUN_IDLE;
                if (o.connected) {
                    robot.command(o.port, 0);
                }
            }
        }
    }

    /**
     * The firmware's sync regulation: two motors in sync with turn ratio 0 are kept in step by
     * slowing the one ahead and speeding up the one behind, in proportion to the difference in
     * their rotation since the command.
     */
    private void correctSyncedPair() {
        Output a = null;
        Output b = null;
        for (Output o : outputs) {
            if (o.connected && o.speed != 0 && o.regulation == NxtTelegram.REGULATION_SYNC && o.turnRatio == 0) {
                if (a == null) {
                    a = o;
                } else if (b == null) {
                    b = o;
                }
            }
        }
        if (a == null || b == null) {
            return;
        }
        double progressA = (a.degrees - a.tachoOffset) * Math.signum(a.speed);
        double progressB = (b.degrees - b.tachoOffset) * Math.signum(b.speed);
        double correction = SYNC_GAIN_PER_SECOND * (progressA - progressB);
        a.speed -= Math.signum(a.speed) * correction;
        b.speed += Math.signum(b.speed) * correction;
    }

    /** Degrees per second of correction per degree that two synced motors are apart. */
    private static final double SYNC_GAIN_PER_SECOND = 25;

    /** The firmware's turn ratio for motors in sync: the first runs at full, the second at 1 − turn/50 (−1 at 100). */
    private double syncFactor(Output o) {
        if (o.regulation != NxtTelegram.REGULATION_SYNC || o.turnRatio == 0) {
            return 1;
        }
        int index = Arrays.asList(outputs).indexOf(o);
        boolean first = true;
        for (int i = 0; i < index; i++) {
            first &= outputs[i].regulation != NxtTelegram.REGULATION_SYNC;
        }
        double t = o.turnRatio;
        if (t > 0) {
            return first ? 1 : 1 - t / 50;
        }
        return first ? 1 + t / 50 : 1;
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
        if (port >= OUTPUTS && port != 0xFF) {
            return status(op, NxtStatus.OUT_OF_RANGE);
        }
        for (int i = 0; i < OUTPUTS; i++) {
            if (port == 0xFF || port == i) {
                Output o = outputs[i];
                o.power = Math.max(-100, Math.min(100, t[3]));
                o.mode = t[4] & 0xFF;
                o.regulation = t[5] & 0xFF;
                o.turnRatio = Math.max(-100, Math.min(100, t[6]));
                o.runState = t[7] & 0xFF;
                o.tachoLimit = LittleEndian.u32(t, 8);
                o.tachoOffset = o.degrees;
            }
        }
        return status(op, NxtStatus.SUCCESS);
    }

    private byte[] getOutputState(byte[] t) {
        int op = NxtTelegram.GETOUTPUTSTATE;
        if (t.length < 3 || (t[2] & 0xFF) >= OUTPUTS) {
            return sized(op, NxtTelegram.GETOUTPUTSTATE_REPLY, t.length < 3 ? NxtStatus.INSANE_PACKET : NxtStatus.OUT_OF_RANGE);
        }
        Output o = outputs[t[2] & 0xFF];
        byte[] r = sized(op, NxtTelegram.GETOUTPUTSTATE_REPLY, NxtStatus.SUCCESS);
        r[3] = t[2];
        r[4] = (byte) o.power;
        r[5] = (byte) o.mode;
        r[6] = (byte) o.regulation;
        r[7] = (byte) o.turnRatio;
        r[8] = (byte) o.runState;
        LittleEndian.putU32(r, 9, o.tachoLimit);
        LittleEndian.putU32(r, 13, Math.round(o.degrees - o.tachoOffset));
        LittleEndian.putU32(r, 17, Math.round(o.degrees - o.blockOffset));
        LittleEndian.putU32(r, 21, Math.round(o.degrees - o.rotationOffset));
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
        if (t[3] != 0) {
            outputs[port].blockOffset = outputs[port].degrees;
        } else {
            outputs[port].rotationOffset = outputs[port].degrees;
        }
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
        boolean distance = txLength >= 2 && (t[5] & 0xFF) == NxtTelegram.ULTRASONIC_ADDRESS && (t[6] & 0xFF) == NxtTelegram.ULTRASONIC_DISTANCE;
        in.pendingRx = rxLength;
        in.bytesReady = 0;
        if (!distance || in.sensor == null) {
            in.pendingRx = -1;
            Arrays.fill(in.lsData, (byte) 0);
            in.bytesReady = rxLength;
        }
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
