package io.robomw.sim.platform;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.GenericMotorPlatform;
import io.robomw.platform.motor.MotorState;
import io.robomw.sim.SimMotors;

import java.util.List;

/**
 * The simulator's motor platform: {@code runImpl} sets the simulated motors' speeds, and
 * {@code pollFeedback} reports their encoders. No I/O, so it runs inline on the simulation thread.
 */
final class SimMotorPlatform extends GenericMotorPlatform {

    private final SimMotors motors;
    /** The ports in the order the platform was built with, and each one's index in the simulated robot. */
    private final int[] robotPorts;

    SimMotorPlatform(PlatformConfig config, SimMotors motors) {
        super(config.robotName(), config.clock(), config.motorPorts());
        this.motors = motors;
        List<String> ports = config.motorPorts();
        this.robotPorts = new int[ports.size()];
        for (int i = 0; i < robotPorts.length; i++) {
            robotPorts[i] = motors.portIndex(ports.get(i));
        }
    }

    @Override
    protected void runImpl(List<MotorState> states) {
        for (MotorState s : states) {
            motors.command(s.port(), s.degreesPerSecond());
        }
    }

    @Override
    protected void pollFeedback() {
        for (int i = 0; i < robotPorts.length; i++) {
            reportDegrees(i, robotPorts[i] < 0 ? 0.0 : motors.degrees(robotPorts[i]));
        }
    }
}
