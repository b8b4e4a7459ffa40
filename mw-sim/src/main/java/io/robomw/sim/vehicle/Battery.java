package io.robomw.sim.vehicle;

/**
 * A lithium-polymer battery as ArduPilot's SITL models it, simply: the charge drawn is counted;
 * the open-circuit voltage falls linearly from 4.2 V to 3.3 V a cell as it empties; the voltage
 * under load sags by the current through an internal resistance. Not thread-safe (the
 * simulation's thread).
 */
public final class Battery {

    /** A full cell's voltage. */
    public static final double FULL_CELL_VOLTS = 4.2;
    /** An empty cell's voltage. */
    public static final double EMPTY_CELL_VOLTS = 3.3;
    /** Internal resistance per cell, ohms. */
    public static final double CELL_OHMS = 0.005;

    private final double capacityWh;
    private final int cells;
    private double usedWh;
    private double amps;

    /**
     * @param capacityWh watt-hours when full
     * @param cells      cells in series
     */
    public Battery(double capacityWh, int cells) {
        this.capacityWh = capacityWh;
        this.cells = cells;
    }

    /**
     * Draws power for a while.
     *
     * @param watts   the power drawn
     * @param seconds for how long
     */
    void draw(double watts, double seconds) {
        double volts = Math.max(1e-3, openVolts());
        amps = watts / volts;
        usedWh = Math.min(capacityWh, usedWh + watts * seconds / 3600);
    }

    private double openVolts() {
        return cells * (EMPTY_CELL_VOLTS + (FULL_CELL_VOLTS - EMPTY_CELL_VOLTS) * remaining());
    }

    /** @return the charge left, 0 to 1 */
    public double remaining() {
        return 1 - usedWh / capacityWh;
    }

    /** @return the voltage under the present load, volts */
    public double volts() {
        return openVolts() - amps * cells * CELL_OHMS;
    }

    /** @return the present current, amperes */
    public double amps() {
        return amps;
    }

    /** @return the energy drawn so far, watt-hours */
    public double usedWh() {
        return usedWh;
    }

    /** @return the charge drawn so far, milliampere-hours (at the nominal 3.7 V a cell) */
    public double usedMah() {
        return usedWh / (cells * 3.7) * 1000;
    }

    /** @return cells in series */
    public int cells() {
        return cells;
    }
}
