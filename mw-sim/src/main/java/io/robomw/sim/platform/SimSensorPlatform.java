package io.robomw.sim.platform;

import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import io.robomw.sim.SimMotors;

/**
 * The simulator's sensor platform: a read is answered at the robot's next cycle with the raw value
 * the described sensor would report (the true value through the inverse of its conversion).
 */
final class SimSensorPlatform extends SensorPlatform {

    private final SimMotors robot;

    SimSensorPlatform(MotorPlatform motors, SimMotors robot) {
        super(motors);
        this.robot = robot;
    }

    /** For a legged robot, which has no motors of its own. */
    SimSensorPlatform(SimMotors robot) {
        this.robot = robot;
    }

    @Override
    public Sensor createSensor(SensorChannel sensorObject) {
        return robot.sensor(sensorObject.name());
    }
}
