package io.robomw.sim.platform;

import io.robomw.api.spi.PlatformConfig;
import io.robomw.api.spi.PlatformProvider;
import io.robomw.api.spi.RobotPlatform;
import io.robomw.platform.BrickPlatform;
import io.robomw.platform.command.HighLevelRobotPlatform;
import io.robomw.platform.motor.MotorPlatform;
import io.robomw.sim.SimMotors;
import io.robomw.sim.SimWorld;

import java.io.IOException;

/**
 * {@code platform: sim}: a robot in a simulated world. The world comes from the platform
 * services ({@link io.robomw.sim.Simulation} passes it); the robot is the world's robot of the
 * same name. A robot with a legged drive gets a platform that takes high-level commands
 * ({@link LeggedSimPlatform}); a vehicle one that flies them on its simulated vehicle
 * ({@link io.robomw.sim.vehicle.VehicleSimPlatform}).
 */
public final class SimPlatformProvider implements PlatformProvider {

    @Override
    public String platformName() {
        return "sim";
    }

    @Override
    public RobotPlatform open(PlatformConfig config) throws IOException {
        SimWorld world = config.services().find(SimWorld.class).orElseThrow(() -> new IOException(
                "robot '" + config.robotName() + "' is on platform 'sim' but no simulated world was given; open it through a simulation "
                        + "(mw sim WORLD.yaml, or Simulation.load(world).robot(name))"));
        SimMotors motors = SimMotors.of(world, config.robotName()).orElseThrow(() -> new IOException(
                "robot '" + config.robotName() + "' is not in world '" + world.description().name() + "' (" + world.description().source() + ")"));
        if (motors.robot().vehicle() != null) {
            io.robomw.sim.SimRobot robot = motors.robot();
            io.robomw.sim.vehicle.VehicleSimPlatform pilot = new io.robomw.sim.vehicle.VehicleSimPlatform(config.robotName(), config.clock(),
                    robot.vehicle(), robot.description().vehicleDrive().orElseThrow());
            HighLevelRobotPlatform platform = new HighLevelRobotPlatform(config, pilot, new SimSensorPlatform(motors), null);
            world.attach(robot, platform.actionThread());
            double dt = world.stepSeconds();
            int index = robot.index();
            java.util.function.IntConsumer control = i -> {
                if (i == index) {
                    pilot.control(dt);
                }
            };
            world.addRobotController(1, control);
            return new SimPlatform.Vehicle(platform, world.lockstep(), robot.vehicle(), () -> world.removeRobotController(control));
        }
        if (motors.robot().quadruped() != null) {
            LeggedSimPlatform legged = new LeggedSimPlatform(config, motors.robot());
            HighLevelRobotPlatform platform = new HighLevelRobotPlatform(config, legged, new SimSensorPlatform(motors), null);
            world.attach(motors.robot(), platform.actionThread());
            return new SimPlatform.HighLevel(platform, world.lockstep());
        }
        MotorPlatform motorPlatform = new MotorPlatform(config, new SimMotorDriver(config, motors));
        BrickPlatform platform = new BrickPlatform(config, motorPlatform, new SimSensorPlatform(motorPlatform, motors), null, null);
        // the world may drive it in a batch until it is addressed one by one; it then reads its encoders with a round of its link side
        world.attach(motors.robot(), platform.actionThread(), () -> {
            try {
                motorPlatform.linkSide().service();
            } catch (java.io.IOException e) {
                throw new java.io.UncheckedIOException("robot '" + config.robotName() + "': its simulated link failed: " + e.getMessage(), e);
            }
        });
        return new SimPlatform(platform, world.lockstep());
    }
}
