package io.robomw.platform.motor;

/**
 * The driver of a {@link MotorBatch}: the hardware face of many robots of one robot file at once,
 * the batch's counterpart of {@link MotorDriver} (a simulator's, whose "hardware" is the world's
 * arrays). Called on the thread that cycles the member named (one thread at a time per member;
 * different members may be driven from different threads at once), never blocking.
 */
public interface BatchMotorDriver {

    /**
     * Sets one member's motors turning at these speeds.
     *
     * @param member the member, by its index in the batch
     * @param speeds the batch's wanted speeds, degrees per second, in the batch's port order: this
     *               member's are {@code speeds[from]} to {@code speeds[from + motors - 1]}; lent for the call only
     * @param from   where this member's speeds start
     */
    void send(int member, double[] speeds, int from);

    /**
     * @param member the member, by its index in the batch
     * @param motor  one of its motors, by its place in the batch's ports
     * @return the motor's encoder now, degrees
     */
    double degrees(int member, int motor);
}
