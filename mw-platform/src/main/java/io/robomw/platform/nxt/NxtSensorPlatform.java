package io.robomw.platform.nxt;

import io.robomw.platform.brick.LittleEndian;
import io.robomw.platform.link.Deadline;
import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import java.io.IOException;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;

/**
 * The NXT's sensor platform: each sensor's port is set up with SETINPUTMODE, and read with
 * GETINPUTVALUES (touch: the boolean scaled value, 1 pressed; light and sound: the normalized
 * value 0..1023; colour: the colour number) or, for the ultrasonic sensor, with an I²C transaction
 * (LSWRITE register 0x42, LSGETSTATUS until ready, LSREAD: centimetres). After SETINPUTMODE the
 * firmware marks a port invalid until it has set the sensor up; reads wait for the valid flag. A
 * brick that restarted (its link reopened to it) has forgotten the setup: its reply names another
 * sensor type, and the port is set up again.
 * Reads run on the caller's thread, one exchange at a time on the brick's channel.
 *
 * <p>Sensor options: {@code floodlight: false} reads a light sensor with its lamp off.
 */
public final class NxtSensorPlatform extends SensorPlatform {

    private static final Logger LOG = LoggerFactory.getLogger(NxtSensorPlatform.class);

    /**
     * How long a reading may stay invalid or an I²C transaction pending. A real brick answers within
     * tens of milliseconds; polls are round trips, so counting them would make the limit depend on
     * the link's speed (a fast pseudo-terminal spends 200 polls in a few milliseconds).
     */
    private static final long MAX_WAIT_NANOS = 1_000_000_000L;

    /** The sensor types the NXT reads on its input ports (its standard sensors), as {@link #createSensor} sets them up. */
    static final java.util.Set<io.robomw.api.SensorType> SUPPORTED = java.util.EnumSet.of(io.robomw.api.SensorType.TOUCH,
            io.robomw.api.SensorType.LIGHT, io.robomw.api.SensorType.SOUND, io.robomw.api.SensorType.COLOR, io.robomw.api.SensorType.SONAR);

    private final NxtBrick brick;

    /**
     * @param motors the motor platform (for tachometers)
     * @param brick  the brick
     */
    public NxtSensorPlatform(MotorPlatform motors, NxtBrick brick) {
        super(motors);
        this.brick = brick;
    }

    /**
     * @param port an input port name
     * @return its NXT input number: S1 = 0 ... S4 = 3
     */
    static int inputPort(String port) {
        String p = port.startsWith("S") ? port.substring(1) : port;
        return switch (p) {
            case "1" -> 0;
            case "2" -> 1;
            case "3" -> 2;
            case "4" -> 3;
            default -> throw new IllegalArgumentException("the NXT has input ports S1 to S4, not '" + port + "'");
        };
    }

    @Override
    public Sensor createSensor(SensorChannel sensor) throws IOException {
        int port = inputPort(sensor.port());
        return switch (sensor.type()) {
            case TOUCH -> analog(sensor, port, NxtTelegram.TYPE_SWITCH, NxtTelegram.MODE_BOOLEAN, Field.SCALED);
            case LIGHT -> analog(sensor, port, Boolean.FALSE.equals(sensor.options().get("floodlight"))
                    ? NxtTelegram.TYPE_LIGHT_INACTIVE : NxtTelegram.TYPE_LIGHT_ACTIVE, NxtTelegram.MODE_RAW, Field.NORMALIZED);
            case SOUND -> analog(sensor, port, NxtTelegram.TYPE_SOUND_DB, NxtTelegram.MODE_RAW, Field.NORMALIZED);
            case COLOR -> analog(sensor, port, NxtTelegram.TYPE_COLORFULL, NxtTelegram.MODE_RAW, Field.SCALED);
            case SONAR -> ultrasonic(port);
            default -> throw new IOException("robot '" + brick.robot() + "': sensor '" + sensor.name() + "': the NXT has no standard "
                    + sensor.type() + " sensor (it supports touch, light, sound, colour and ultrasonic)");
        };
    }

    /** Which value of a GETINPUTVALUES reply a sensor reports. */
    private enum Field {
        NORMALIZED(NxtTelegram.DATA_OFFSET + NxtTelegram.IN_NORMALIZED),
        SCALED(NxtTelegram.DATA_OFFSET + NxtTelegram.IN_SCALED);

        private final int offset;

        Field(int offset) {
            this.offset = offset;
        }
    }

    private Sensor analog(SensorChannel sensor, int port, int type, int mode, Field field) throws IOException {
        setUp(port, type, mode);
        return () -> read(() -> {
            byte[] reply = validInputValues(port, type, mode);
            return (double) (field == Field.SCALED ? LittleEndian.s16(reply, field.offset) : LittleEndian.u16(reply, field.offset));
        });
    }

    private void setUp(int port, int type, int mode) throws IOException {
        brick.request(NxtTelegram.setInputMode(true, port, type, mode), NxtTelegram.STATUS_REPLY, port);
    }

    /**
     * Reads a port's values until the firmware marks them valid. A brick that answers for another
     * sensor type than the one set up has forgotten the setup (it was switched off and on, and its
     * link reopened to it): the port is set up again, and the read waits for it.
     */
    private byte[] validInputValues(int port, int type, int mode) throws IOException {
        Deadline deadline = Deadline.after(Duration.ofNanos(MAX_WAIT_NANOS)); // the brick's time to read its port: wall-clock
        int reads = 0;
        do {
            byte[] reply = brick.request(NxtTelegram.getInputValues(port), NxtTelegram.GETINPUTVALUES_REPLY, port);
            reads++;
            int setFor = reply[NxtTelegram.DATA_OFFSET + NxtTelegram.IN_TYPE] & 0xFF;
            if (setFor != type) {
                LOG.info("robot '{}': the NXT's input S{} is set up for sensor type 0x{} instead of 0x{} (the brick restarted?); setting it up again",
                        brick.robot(), port + 1, Integer.toHexString(setFor), Integer.toHexString(type));
                setUp(port, type, mode);
                continue;
            }
            if (reply[NxtTelegram.DATA_OFFSET + NxtTelegram.IN_VALID] != 0) {
                return reply;
            }
        } while (!deadline.expired());
        throw new IOException("robot '" + brick.robot() + "': NXT input port " + (port + 1) + " stayed invalid for " + MAX_WAIT_NANOS / 1_000_000 + " ms (" + reads + " reads)");
    }

    private Sensor ultrasonic(int port) throws IOException {
        setUp(port, NxtTelegram.TYPE_LOWSPEED_9V, NxtTelegram.MODE_RAW);
        return () -> read(() -> {
            validInputValues(port, NxtTelegram.TYPE_LOWSPEED_9V, NxtTelegram.MODE_RAW);
            brick.request(NxtTelegram.lsWrite(true, port, 1, (byte) NxtTelegram.ULTRASONIC_ADDRESS, (byte) NxtTelegram.ULTRASONIC_DISTANCE),
                    NxtTelegram.STATUS_REPLY, port);
            Deadline deadline = Deadline.after(Duration.ofNanos(MAX_WAIT_NANOS));
            int polls = 0;
            do {
                polls++;
                byte[] status = brick.requestAllowing(NxtTelegram.lsGetStatus(port), NxtTelegram.LSGETSTATUS_REPLY, port);
                int s = NxtTelegram.status(status);
                if (s == NxtStatus.SUCCESS && (status[NxtTelegram.DATA_OFFSET + NxtTelegram.LS_BYTES_READY] & 0xFF) >= 1) {
                    byte[] data = brick.request(NxtTelegram.lsRead(port), NxtTelegram.LSREAD_REPLY, port);
                    return (double) (data[NxtTelegram.DATA_OFFSET + NxtTelegram.LS_DATA] & 0xFF);
                }
                if (s != NxtStatus.PENDING && s != NxtStatus.SUCCESS) {
                    throw new NxtException(brick.robot(), NxtTelegram.LSGETSTATUS, port, s);
                }
            } while (!deadline.expired());
            throw new IOException("robot '" + brick.robot() + "': the ultrasonic sensor on S" + (port + 1) + " did not answer within "
                    + MAX_WAIT_NANOS / 1_000_000 + " ms (" + polls + " polls)");
        });
    }

    /** A read that may fail with I/O. */
    @FunctionalInterface
    private interface Read {
        double run() throws IOException;
    }

    private CompletableFuture<Double> read(Read read) {
        try {
            return CompletableFuture.completedFuture(read.run());
        } catch (IOException e) {
            return CompletableFuture.failedFuture(new RobotLinkException("robot '" + brick.robot() + "': reading the NXT failed: " + e.getMessage(), e));
        } catch (RuntimeException e) {
            return CompletableFuture.failedFuture(e);
        }
    }
}
