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

    SimMotorPlatform(PlatformConfig config, SimMotors motors) {
        super(config.robotName(), config.clock(), config.motorPorts());
        this.motors = motors;
    }

    @Override
    protected void runImpl(List<MotorState> states) {
        for (MotorState s : states) {
            motors.command(s.port(), s.degreesPerSecond());
        }
    }

    @Override
    protected void pollFeedback() {
        for (String port : ports()) {
            reportDegrees(port, motors.degrees(port));
        }
    }
}
