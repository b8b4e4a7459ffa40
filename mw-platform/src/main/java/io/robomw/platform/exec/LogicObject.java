package io.robomw.platform.exec;

/**
 * A condition of a container, evaluated every cycle until it holds: for example "motor B has
 * turned 2046°; then stop it". It may act at the moment it holds (stop its motor). A container
 * finishes when all its logic objects hold. Called on the execution action thread; must not block.
 */
@FunctionalInterface
public interface LogicObject {

    /**
     * @param nowNanos the action thread's clock at the start of this cycle
     * @return true once the condition holds; it is not evaluated again after that
     */
    boolean evaluate(long nowNanos);
}
