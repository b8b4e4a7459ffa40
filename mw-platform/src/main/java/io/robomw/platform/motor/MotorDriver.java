package io.robomw.platform.motor;

import java.io.IOException;
import java.util.List;

/**
 * What a platform writer implements for a brick's motors: the paper's {@code runImpl(motors)},
 * with the brick's feedback and its link's timing. A driver is a small object the platform calls,
 * as Agrona's {@code AgentRunner} calls its {@code Agent}: the {@link MotorPlatform} turns commands
 * into containers and motor states, and the brick's {@code LinkAgent} owns the thread that calls
 * {@link #send} and {@link #poll}; the driver only encodes, exchanges and decodes.
 *
 * <h2>Threads</h2>
 * {@link #send} and {@link #poll} are called on the link side only (the link agent's thread, or a
 * simulation's cycling thread), one at a time: {@code send} with each cycle's changed states, then
 * {@code poll}; or {@code poll} alone when nothing changed. {@link #timing()} and
 * {@link #hasEncoder} may be called on any thread.
 *
 * <h2>Failures</h2>
 * An {@link IOException} means the link failed: the states are kept and sent again once the link
 * agent has reopened it. A {@link io.robomw.api.RobotException} means the brick answered but
 * refused (an error status): the commands concerned fail with it, and the states are not sent again.
 * Anything else is a bug of the driver: reported to the failure policy, and the link goes on.
 */
public interface MotorDriver {

    /**
     * Pushes motor states to the brick: the states that changed since the last call (and those a
     * stop just in time or a brick's own stop added), in the port order of the description, all of
     * one cycle, so motors started together start together. A driver that reads the brick in the
     * same exchange (a pipelined poll) reports the readings to {@code feedback}.
     *
     * @param states   the changed motors
     * @param feedback where readings and the brick's own stops go
     * @throws IOException if the link failed
     */
    void send(List<MotorState> states, FeedbackSink feedback) throws IOException;

    /**
     * Reads the brick's feedback (encoders, whether a limited rotation ended) and keeps the brick
     * alive; called after every {@link #send}, and once a cycle or so while nothing changes.
     *
     * @param feedback where readings and the brick's own stops go
     * @return how many motors it is watching move (running, or settling after a stop): 0 when every
     *         motor is at rest, so the link agent may come round less often
     * @throws IOException if the link failed
     */
    int poll(FeedbackSink feedback) throws IOException;

    /**
     * @return the link's timing as the driver knows it (its measured delays, what the brick does by
     *         itself); the same object every time, whose figures may change as the driver measures
     */
    LinkTiming timing();

    /**
     * @param port a motor port
     * @return whether the motor's rotation is read back (by its encoder, or a counter on an input);
     *         the same for the whole life of the platform. The default: every motor
     */
    default boolean hasEncoder(String port) {
        return true;
    }
}
