package io.robomw.sim.platform;

import io.robomw.api.SensorType;
import io.robomw.api.spi.SensorChannel;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.platform.sensor.Sensor;
import io.robomw.platform.sensor.SensorPlatform;
import io.robomw.platform.sensor.Sensors;
import io.robomw.sim.SensorModel;
import io.robomw.sim.SimMotors;

import java.io.IOException;
import java.util.List;
import java.util.Map;

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

    /**
     * One reader for all of a robot's sensors ({@link SimMotors#readRaw}), its models shared by
     * every robot of the robot file, when the description's sensors are exactly the model's (no
     * motor encoder among them, which the motor platform answers): the same reads as a reader a
     * sensor, without a map and readers a robot. Otherwise the standard map.
     */
    @Override
    public Sensors createSensors(List<SensorChannel> channels) throws IOException {
        Map<String, SensorModel> models = robot.robot().sensors();
        boolean same = channels.size() == models.size();
        for (SensorChannel c : channels) {
            same &= c.type() != SensorType.TACHO && models.containsKey(c.name());
        }
        return same ? robot::readRaw : super.createSensors(channels);
    }

    @Override
    public Sensor createSensor(SensorChannel sensorObject) {
        return robot.sensor(sensorObject.name());
    }
}
