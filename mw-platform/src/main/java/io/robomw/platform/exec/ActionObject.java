package io.robomw.platform.exec;

/**
 * An action of a container, run once when the container starts: for example "start motors B and
 * C at 300°/s". Called on the execution action thread; must not block.
 */
@FunctionalInterface
public interface ActionObject {

    /**
     * @param nowNanos the action thread's clock at the start of this cycle
     */
    void start(long nowNanos);
}
