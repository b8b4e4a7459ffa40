package io.robomw.agents.messaging.robot;

import java.io.Serializable;

/**
 * The answer to a {@link RobotCall}: a value or a failure.
 *
 * @param value   the result, or {@code null}
 * @param failure what the robot threw (see {@link RobotFailures}), or {@code null}
 */
public record RobotReply(Serializable value, Throwable failure) implements Serializable {
}
