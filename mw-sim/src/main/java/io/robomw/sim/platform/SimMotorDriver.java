package io.robomw.sim.platform;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.platform.motor.FeedbackSink;
import io.robomw.platform.motor.LinkTiming;
import io.robomw.platform.motor.MotorDriver;
import io.robomw.platform.motor.MotorState;
import io.robomw.sim.SimMotors;

import java.util.List;

/**
 * The simulator's motor driver: {@code send} sets the simulated motors' speeds, and {@code poll}
 * reports their encoders. No I/O and no delay ({@link LinkTiming#NONE}): the link agent runs it
 * inline, on the thread that cycles the world, and allocates nothing per cycle.
 */
final class SimMotorDriver implements MotorDriver {

    private final SimMotors motors;
    /** Each port's index in the simulated robot, in the order of the description's motor ports. */
    private final int[] robotPorts;

    SimMotorDriver(PlatformConfig config, SimMotors motors) {
        this.motors = motors;
        List<String> ports = config.motorPorts();
        this.robotPorts = new int[ports.size()];
        for (int i = 0; i < robotPorts.length; i++) {
            robotPorts[i] = motors.portIndex(ports.get(i));
        }
    }

    @Override
    public void send(List<MotorState> states, FeedbackSink feedback) {
        for (int i = 0; i < states.size(); i++) { // no iterator: every robot's every batch
            MotorState s = states.get(i);
            motors.command(s.port(), s.degreesPerSecond());
        }
    }

    /** @return 0: the simulation cycles it whatever it says */
    @Override
    public int poll(FeedbackSink feedback) {
        for (int i = 0; i < robotPorts.length; i++) {
            feedback.degrees(i, robotPorts[i] < 0 ? 0.0 : motors.degrees(robotPorts[i]));
        }
        return 0;
    }

    @Override
    public LinkTiming timing() {
        return LinkTiming.NONE;
    }
}
