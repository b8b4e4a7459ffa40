package io.robomw.sim.programs;

import io.robomw.api.Robot;

/**
 * Drives a square: four times forwards by the side, then a quarter turn left. A blocking program
 * for {@link io.robomw.sim.Simulation#run}; it works unchanged on any robot.
 *
 * @param robot the robot
 * @param side  side of the square, metres
 * @param speed metres per second
 */
public record SquareProgram(Robot robot, double side, double speed) implements Runnable {

    @Override
    public void run() {
        for (int i = 0; i < 4; i++) {
            robot.move(side, speed);
            robot.turn(Math.PI / 2, Math.min(1.0, speed / 0.056 / 2));
        }
    }
}
