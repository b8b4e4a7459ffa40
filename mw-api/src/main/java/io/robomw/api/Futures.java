package io.robomw.api;

import java.time.Duration;
import java.util.concurrent.CancellationException;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * Turns the futures of the {@code ...Async} verbs into the blocking forms: waits with a deadline,
 * and re-throws the cause of a failure as it was thrown, so blocking callers see
 * {@link CommandPreemptedException} or {@link UnsupportedActionException} rather than a wrapper.
 *
 * <h2>A wait that ends early ends its command</h2>
 * Cancelling the future of an {@code ...Async} verb ends the command it stands for: a motion's
 * motors brake at the platform's next cycle. So when a blocking verb's wait ends without the
 * command ending (the caller's thread was interrupted, or the deadline passed), the future is
 * cancelled before the exception is thrown: an interrupted {@code move} does not drive on.
 */
public final class Futures {

    /** The least a blocking motion waits beyond three times its own duration at speed. */
    public static final Duration MOTION_SLACK = Duration.ofSeconds(10);
    /** How long a blocking verb without a duration of its own (a named action, a sensor read) waits at most. */
    public static final Duration DEFAULT_TIMEOUT = Duration.ofMinutes(5);

    private Futures() {
    }

    /**
     * The deadline of a blocking motion: three times its duration at the commanded speed, plus
     * {@link #MOTION_SLACK} (the platform fails a blocked motor well before, at three times plus
     * 2 s; this is the last word for the caller's thread).
     *
     * @param seconds the motion's duration at speed ({@code |distance| / speed}); not finite gives {@link #DEFAULT_TIMEOUT}
     * @return the deadline
     */
    public static Duration motionTimeout(double seconds) {
        if (!Double.isFinite(seconds) || seconds < 0) {
            return DEFAULT_TIMEOUT;
        }
        return Duration.ofNanos(Math.round(3e9 * Math.min(seconds, 1e8))).plus(MOTION_SLACK);
    }

    /**
     * Waits for a future and returns its value, for at most {@code timeout}. If the wait ends
     * first (timeout or interrupt), the future is cancelled, which ends the command it stands for.
     *
     * @param future  the future
     * @param timeout how long to wait
     * @param what    what is awaited, for the message ({@code move(0.500, 0.200)})
     * @param <T>     its value type
     * @return its value
     * @throws RobotException (or a subclass) if the future failed with one; other failures are
     *                        wrapped in a RobotException; a RobotException saying so if the
     *                        deadline passed or the thread was interrupted (its interrupt status
     *                        is set again)
     */
    public static <T> T await(CompletableFuture<T> future, Duration timeout, String what) {
        try {
            return future.get(timeout.toNanos(), TimeUnit.NANOSECONDS);
        } catch (InterruptedException e) {
            future.cancel(true);
            Thread.currentThread().interrupt();
            throw new RobotException("interrupted while waiting for " + what + "; it was cancelled (a motion's motors brake)", e);
        } catch (TimeoutException e) {
            future.cancel(true);
            throw new RobotException(what + " did not complete within " + timeout.toMillis() + " ms; it was cancelled (a motion's motors brake)", e);
        } catch (CancellationException e) {
            throw new RobotException(what + " was cancelled", e);
        } catch (ExecutionException e) {
            Throwable cause = e.getCause();
            if (cause instanceof RuntimeException runtime) {
                throw runtime;
            }
            if (cause instanceof Error error) {
                throw error;
            }
            throw new RobotException(what + ": " + cause.getMessage(), cause);
        }
    }

    /**
     * Makes cancelling a future derived from a command's future (by {@code thenApply},
     * {@code whenComplete}...) cancel the command's own, so that the derived future keeps the
     * contract of the {@code ...Async} verbs: cancelling it ends the command.
     *
     * @param derived the future handed to the caller
     * @param source  the command's own future
     * @param <T>     the derived value type
     * @return {@code derived}
     */
    public static <T> CompletableFuture<T> cancelling(CompletableFuture<T> derived, CompletableFuture<?> source) {
        derived.whenComplete((v, e) -> {
            if (e instanceof CancellationException && !source.isDone()) {
                source.cancel(true);
            }
        });
        return derived;
    }
}
