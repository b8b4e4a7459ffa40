package io.robomw.config.robot;

import io.robomw.api.RobotException;
import io.robomw.api.RobotLinkException;

import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * Waits for a safety stop to reach the hardware, as {@link io.robomw.api.Motion#stop()} promises:
 * with a deadline, and with a {@link RobotLinkException} naming the robot when it does not get
 * there. Unlike a motion's wait, a wait that ends early never cancels what it waited for: the stop
 * goes on. Stateless.
 */
final class Stops {

    private Stops() {
    }

    /**
     * @param handed  the platform's {@code stopAll()} future: completes once the stop is handed to the hardware
     * @param timeout how long to wait
     * @param robot   the robot's name, for the messages
     * @throws RobotLinkException naming the robot if the stop failed or did not complete in time
     * @throws RobotException     if the thread was interrupted (its interrupt status is set again;
     *                            the stop goes on)
     */
    static void awaitHanded(CompletableFuture<Void> handed, Duration timeout, String robot) {
        try {
            handed.get(timeout.toNanos(), TimeUnit.NANOSECONDS);
        } catch (TimeoutException e) {
            throw new RobotLinkException("robot '" + robot + "': its stop was not handed to the hardware within "
                    + timeout.toMillis() + " ms; check its link", e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new RobotException("interrupted while waiting for robot '" + robot + "' to hand its stop to the hardware; the stop goes on", e);
        } catch (ExecutionException e) {
            Throwable cause = e.getCause();
            if (cause instanceof RobotLinkException link) {
                throw link;
            }
            throw new RobotLinkException("robot '" + robot + "': its stop could not be handed to the hardware: " + cause, cause);
        }
    }
}
