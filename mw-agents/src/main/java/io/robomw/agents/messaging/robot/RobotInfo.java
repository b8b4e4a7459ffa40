package io.robomw.agents.messaging.robot;

import io.robomw.api.Capability;
import io.robomw.api.Position;
import io.robomw.api.Robot;
import io.robomw.api.SensorInfo;
import io.robomw.api.SensorType;

import java.io.Serializable;
import java.util.ArrayList;
import java.util.List;

/**
 * What a remote robot is, fetched once when it is opened.
 *
 * @param name         the robot's name
 * @param capabilities what it is built for
 * @param sensors      its sensors
 * @param actions      its named actions
 */
public record RobotInfo(String name, ArrayList<Capability> capabilities, ArrayList<Sensor> sensors, ArrayList<String> actions)
        implements Serializable {

    /** One sensor, as {@link SensorInfo} (which is not serializable) says it. @param name its name @param type what it measures @param position where it sits */
    public record Sensor(String name, SensorType type, Position position) implements Serializable {
    }

    static RobotInfo of(Robot robot) {
        ArrayList<Sensor> sensors = new ArrayList<>();
        for (SensorInfo s : robot.sensors()) {
            sensors.add(new Sensor(s.name(), s.type(), s.position()));
        }
        return new RobotInfo(robot.name(), new ArrayList<>(robot.capabilities()), sensors, new ArrayList<>(robot.actions()));
    }

    List<SensorInfo> sensorInfos() {
        return sensors.stream().map(s -> new SensorInfo(s.name(), s.type(), s.position())).toList();
    }

    static List<Class<?>> classes() {
        return List.of(RobotInfo.class, Sensor.class, Capability.class, Position.class, SensorType.class);
    }
}
