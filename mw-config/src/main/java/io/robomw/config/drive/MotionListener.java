package io.robomw.config.drive;

import io.robomw.api.Futures;

import java.util.concurrent.CompletableFuture;

/**
 * Hears of the motions a drive commands: the pose trackers (wheel odometry, a legged robot's dead
 * reckoning) listen to their drive as leJOS's {@code OdometryPoseProvider} listens to its pilot's
 * {@code moveStarted}/{@code moveStopped}, rather than riding along in every verb.
 *
 * <h2>Threads</h2>
 * A motion starts on the thread that commands it and ends on whichever thread ends its command:
 * usually the platform's execution action thread, which runs every robot's real-time loop (a
 * simulation's one thread cycles ten thousand robots). So the two callbacks differ:
 * <ul>
 *   <li>{@link #motionStarted} and {@link #halted} run on the commanding thread, before the
 *   command is handed to the platform (or after the stop was); they may integrate, under a lock
 *   the pose's readers also take;</li>
 *   <li>{@link #motionEnded} only records what the tracker needs of the boundary (encoder readings,
 *   the time), lock-free and without blocking; the tracker integrates it later, on a thread that
 *   asks for the pose or commands the next motion.</li>
 * </ul>
 * Implementations must not throw: a failure to record a boundary loses only its precision.
 */
public interface MotionListener {

    /** A listener that hears nothing: a drive without a pose estimate (wheels without encoders). */
    MotionListener NONE = new MotionListener() {
        @Override
        public void motionStarted(Movement movement) {
        }

        @Override
        public void motionEnded(Movement movement, MotionEnd end) {
        }

        @Override
        public void halted() {
        }

        @Override
        public CompletableFuture<Void> endOf(CompletableFuture<Void> command, Movement movement) {
            return command;
        }
    };

    /**
     * A motion is about to be handed to the platform; it ends the one under way, if any, for the
     * pose. Called on the commanding thread.
     *
     * @param movement the motion
     */
    void motionStarted(Movement movement);

    /**
     * A motion's command ended. Called on the thread that ended it (often the action thread):
     * records, lock-free, and returns.
     *
     * @param movement the motion, as it was started
     * @param end      whether it did all it was commanded to
     */
    void motionEnded(Movement movement, MotionEnd end);

    /**
     * The robot was stopped: the motion under way ended now. Called on the thread that stopped it,
     * once the stop was handed to the hardware.
     */
    void halted();

    /**
     * Has this listener hear of a command's end.
     *
     * @param command  the platform's future of the motion's command
     * @param movement the motion, as it was started
     * @return a future that completes as the command does, once the end was recorded (so a caller
     *         that waited for it finds the boundary in the pose); cancelling it cancels the
     *         command ({@link Futures#cancelling})
     */
    default CompletableFuture<Void> endOf(CompletableFuture<Void> command, Movement movement) {
        return Futures.cancelling(command.whenComplete((v, e) -> motionEnded(movement, e == null ? MotionEnd.COMPLETED : MotionEnd.ENDED_EARLY)),
                command);
    }
}
