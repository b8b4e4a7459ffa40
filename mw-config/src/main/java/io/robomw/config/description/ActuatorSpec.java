package io.robomw.config.description;

import java.util.Map;
import java.util.OptionalDouble;

/**
 * An extra actuator (a gripper, an arm) on a motor port, with named actions.
 *
 * @param name    unique within the robot
 * @param port    the motor port
 * @param actions its actions by name
 */
public record ActuatorSpec(String name, String port, Map<String, Action> actions) {

    /** Copies the actions. */
    public ActuatorSpec {
        actions = Map.copyOf(actions);
    }

    /**
     * A named action: turn the actuator's motor by a fixed angle, or by an angle given when the
     * action is performed.
     *
     * @param degrees          motor degrees to turn (signed), or empty when the angle is the
     *                         action's argument (radians, as every API angle)
     * @param degreesPerSecond motor speed
     */
    public record Action(OptionalDouble degrees, double degreesPerSecond) {
    }
}
