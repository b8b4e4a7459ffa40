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

    /** Radians per second of the quarter turns: slow enough for any small robot's wheels. */
    public static final double TURN_SPEED = 1.0;

    @Override
    public void run() {
        for (int i = 0; i < 4; i++) {
            robot.move(side, speed);
            robot.turn(Math.PI / 2, TURN_SPEED);
        }
    }
}
