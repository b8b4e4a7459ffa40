package io.robomw.console.foxglove;

import java.util.Set;

/**
 * The robots a Foxglove client may drive by publishing Twists (a teleop panel), and how. The
 * server calls {@link #drive} on its own drive thread, never on a connection's, so a robot reached
 * over a network may take its time to answer.
 */
public interface Teleop {

    /** @return the names of the robots clients may drive (none: the server offers no clientPublish) */
    Set<String> robots();

    /**
     * Drives a robot continuously ({@code Robot.drive}): it keeps going until the next call, and
     * stops by itself when no call comes within its watchdog's timeout (0.5 s by default), so a
     * client that stops publishing stops the robot.
     *
     * @param robot   one of {@link #robots()}
     * @param linear  m/s, forwards positive
     * @param angular rad/s, left positive
     * @throws Exception with a message for the client, if the robot cannot (too fast, no drive, not answering)
     */
    void drive(String robot, double linear, double angular) throws Exception;

    /** No robots: the server only sends. */
    Teleop NONE = new Teleop() {
        @Override
        public Set<String> robots() {
            return Set.of();
        }

        @Override
        public void drive(String robot, double linear, double angular) {
            throw new IllegalStateException("this server drives no robots");
        }
    };
}
