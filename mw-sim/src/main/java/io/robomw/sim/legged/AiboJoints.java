package io.robomw.sim.legged;

import java.util.ArrayList;
import java.util.List;

/**
 * The joints of a Sony Aibo ERS-7 as its URBI server names them, with their ranges (degrees,
 * rounded from the ERS-7 model information) and the leg angles of each posture (the emulator's
 * choice: a plausible pose, not measured).
 *
 * <table>
 *   <caption>joints</caption>
 *   <tr><th>device</th><th>what</th><th>range, °</th></tr>
 *   <tr><td>{@code legLF1 legRF1}</td><td>front shoulder (rotator)</td><td>−115 … 130</td></tr>
 *   <tr><td>{@code legLH1 legRH1}</td><td>hind hip (rotator)</td><td>−130 … 115</td></tr>
 *   <tr><td>{@code legXX2}</td><td>abductor</td><td>−10 … 88</td></tr>
 *   <tr><td>{@code legXX3}</td><td>knee</td><td>−25 … 122</td></tr>
 *   <tr><td>{@code neck}</td><td>neck tilt</td><td>−80 … 3</td></tr>
 *   <tr><td>{@code headPan}, {@code headTilt}</td><td>head</td><td>−93 … 93, −20 … 50</td></tr>
 *   <tr><td>{@code tailPan}, {@code tailTilt}</td><td>tail</td><td>−60 … 60, 0 … 65</td></tr>
 *   <tr><td>{@code mouth}</td><td>jaw</td><td>−55 … −3</td></tr>
 * </table>
 */
public final class AiboJoints {

    private AiboJoints() {
    }

    /**
     * One joint.
     *
     * @param device   its URBI name
     * @param min      the lowest angle, degrees
     * @param max      the highest angle, degrees
     * @param leg      whether it is a leg joint (the gait drives it)
     * @param front    for a leg: whether it is a front leg
     * @param diagonal for a leg: whether it belongs to the pair LF + RH (which trots in phase)
     * @param segment  for a leg: 1 shoulder/hip, 2 abductor, 3 knee; 0 otherwise
     */
    public record Spec(String device, double min, double max, boolean leg, boolean front, boolean diagonal, int segment) {

        /**
         * @param degrees an angle
         * @return it within the range
         */
        public double clamp(double degrees) {
            return Math.max(min, Math.min(max, degrees));
        }
    }

    /** Every joint, legs first (LF, LH, RF, RH, each 1 to 3), then head, tail and mouth. */
    public static final List<Spec> ALL = build();

    private static List<Spec> build() {
        List<Spec> out = new ArrayList<>();
        for (String leg : List.of("LF", "LH", "RF", "RH")) {
            boolean front = leg.endsWith("F");
            boolean diagonal = leg.equals("LF") || leg.equals("RH");
            out.add(new Spec("leg" + leg + "1", front ? -115 : -130, front ? 130 : 115, true, front, diagonal, 1));
            out.add(new Spec("leg" + leg + "2", -10, 88, true, front, diagonal, 2));
            out.add(new Spec("leg" + leg + "3", -25, 122, true, front, diagonal, 3));
        }
        out.add(new Spec("neck", -80, 3, false, false, false, 0));
        out.add(new Spec("headPan", -93, 93, false, false, false, 0));
        out.add(new Spec("headTilt", -20, 50, false, false, false, 0));
        out.add(new Spec("tailPan", -60, 60, false, false, false, 0));
        out.add(new Spec("tailTilt", 0, 65, false, false, false, 0));
        out.add(new Spec("mouth", -55, -3, false, false, false, 0));
        return List.copyOf(out);
    }

    /**
     * @param posture a posture
     * @param leg     a leg joint
     * @return its angle in that posture, degrees
     */
    static double pose(Quadruped.Posture posture, Spec leg) {
        return switch (posture) {
            case STAND -> switch (leg.segment()) {
                case 1 -> leg.front() ? 5 : -5;
                case 2 -> 8;
                default -> 35;
            };
            case SIT -> switch (leg.segment()) {
                case 1 -> leg.front() ? -20 : -100;
                case 2 -> 8;
                default -> leg.front() ? 30 : 110;
            };
            case LIE -> switch (leg.segment()) {
                case 1 -> leg.front() ? 90 : -90;
                case 2 -> 10;
                default -> 10;
            };
        };
    }
}
