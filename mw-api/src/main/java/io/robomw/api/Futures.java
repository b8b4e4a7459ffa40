package io.robomw.api;

import java.util.concurrent.CancellationException;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;

/**
 * Turns the futures of the {@code ...Async} verbs into the blocking forms: waits, and re-throws
 * the cause of a failure as it was thrown, so blocking callers see {@link CommandPreemptedException}
 * or {@link UnsupportedActionException} rather than a wrapper.
 */
public final class Futures {

    private Futures() {
    }

    /**
     * Waits for a future and returns its value.
     *
     * @param future the future
     * @param <T>    its value type
     * @return its value
     * @throws RobotException (or a subclass) if the future failed with one; other failures are wrapped in a RobotException
     */
    public static <T> T await(CompletableFuture<T> future) {
        try {
            return future.get();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            future.cancel(false);
            throw new RobotException("interrupted while waiting for the robot", e);
        } catch (CancellationException e) {
            throw new RobotException("the command was cancelled", e);
        } catch (ExecutionException e) {
            Throwable cause = e.getCause();
            if (cause instanceof RuntimeException runtime) {
                throw runtime;
            }
            if (cause instanceof Error error) {
                throw error;
            }
            throw new RobotException(String.valueOf(cause.getMessage()), cause);
        }
    }
}
