package io.robomw.platform.ft.txt;

import io.robomw.api.RobotLinkException;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;

import java.io.IOException;
import java.util.Locale;
import java.util.concurrent.CompletableFuture;

/**
 * The TXT's sensor platform: each sensor's universal input (I1..I8) is put in the mode its type
 * needs with updateConfig when the robot opens, and read from the inputs of the cyclic exchange.
 *
 * <table>
 *   <caption>Input modes by sensor type</caption>
 *   <tr><th>type</th><th>mode</th><th>raw value</th></tr>
 *   <tr><td>touch</td><td>switch (resistance, digital)</td><td>1 pressed, 0 released</td></tr>
 *   <tr><td>sonar</td><td>ultrasonic</td><td>centimetres</td></tr>
 *   <tr><td>light, infrared, color, sound</td><td>voltage (analog)</td><td>millivolts, 0..10000</td></tr>
 * </table>
 *
 * The option {@code input: voltage | resistance | switch | ultrasonic} picks another mode
 * (a photoresistor reads in ohms with {@code input: resistance}). Gyro and compass sensors are
 * refused: the TXT's inputs do not read them.
 *
 * <p>A read answers from the last exchange's inputs when they are fresh (less than
 * {@link #FRESH_NANOS} old and taken in the sensor's mode); otherwise it runs an exchange itself on
 * the caller's thread. It never waits for the link thread, and a link that is down fails it with
 * {@link RobotLinkException}.
 */
public final class TxtSensorPlatform extends SensorPlatform {

    /** How old the last exchange's inputs may be for a read to use them: 100 ms. */
    static final long FRESH_NANOS = 100_000_000L;

    private final TxtMotorDriver driver;
    private final FeedbackSink feedback;
    private final TxtController controller;

    /** A universal input mode. */
    enum InputMode {
        /** A switch: resistance mode, digital; 1 closed. */
        SWITCH(TxtProtocol.MODE_RESISTANCE, true),
        /** Voltage, analog: millivolts. */
        VOLTAGE(TxtProtocol.MODE_VOLTAGE, false),
        /** Resistance, analog: ohms. */
        RESISTANCE(TxtProtocol.MODE_RESISTANCE, false),
        /** The ultrasonic distance sensor: centimetres. */
        ULTRASONIC(TxtProtocol.MODE_ULTRASONIC, false);

        private final int mode;
        private final boolean digital;

        InputMode(int mode, boolean digital) {
            this.mode = mode;
            this.digital = digital;
        }
    }

    /**
     * @param motors     the motor platform (for tachometers, and where the encoders an exchange reads go)
     * @param driver     the motor driver, which runs the exchange
     * @param controller the TXT
     */
    public TxtSensorPlatform(MotorPlatform motors, TxtMotorDriver driver, TxtController controller) {
        super(motors);
        this.driver = driver;
        this.feedback = motors.feedback();
        this.controller = controller;
    }

    /**
     * @param sensor a sensor of the description
     * @return the input mode it is read in
     * @throws IllegalArgumentException if its type has no mode or its {@code input} option is unknown
     */
    static InputMode modeOf(SensorChannel sensor) {
        Object option = sensor.options().get("input");
        if (option != null) {
            try {
                return InputMode.valueOf(option.toString().toUpperCase(Locale.ROOT));
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException("sensor '" + sensor.name() + "': option input must be voltage, resistance, switch or ultrasonic, got '"
                        + option + "'", e);
            }
        }
        return switch (sensor.type()) {
            case TOUCH -> InputMode.SWITCH;
            case SONAR -> InputMode.ULTRASONIC;
            case LIGHT, INFRARED, COLOR, SOUND -> InputMode.VOLTAGE;
            default -> throw new IllegalArgumentException("sensor '" + sensor.name() + "': the TXT's inputs do not read a " + sensor.type()
                    + " sensor (they read switches, voltages, resistances and the ultrasonic sensor)");
        };
    }

    @Override
    public Sensor createSensor(SensorChannel sensor) throws IOException {
        int input;
        InputMode mode;
        try {
            input = TxtPorts.input(sensor.port());
            mode = modeOf(sensor);
        } catch (IllegalArgumentException e) {
            throw new IOException("robot '" + controller.robot() + "': " + e.getMessage(), e);
        }
        int generation = controller.configureInput(input, mode.mode, mode.digital);
        return () -> read(sensor.name(), input, generation);
    }

    private CompletableFuture<Double> read(String name, int input, int generation) {
        TxtMotorDriver.Inputs in = driver.inputs();
        if (in == null || in.generation() < generation || driver.ageNanos(in) > FRESH_NANOS) {
            try {
                driver.exchangeNow(feedback);
            } catch (IOException e) {
                return CompletableFuture.failedFuture(new RobotLinkException("robot '" + controller.robot() + "': reading sensor '" + name
                        + "' on I" + (input + 1) + " failed: " + e.getMessage(), e));
            } catch (RuntimeException e) {
                return CompletableFuture.failedFuture(e);
            }
            in = driver.inputs();
        }
        return CompletableFuture.completedFuture((double) in.values()[input]);
    }
}
