package io.robomw.sim.physics;

/**
 * The cosine and sine of a body's angle, as the swarm engine computes them at every step for
 * every turning body: plain Java arithmetic (so the same bits on every processor and compiler, as
 * {@link StrictMath} gives), without {@link StrictMath}'s native call, which cost more than the
 * rest of a body's integration.
 *
 * <p>The angle is reduced to [-π/4, π/4] by the nearest multiple of π/2 (π/2 in two parts, as
 * fdlibm's {@code __ieee754_rem_pio2} does for small arguments), then the reduced angle's sine and
 * cosine are fdlibm's kernel polynomials ({@code __kernel_sin}, {@code __kernel_cos}, the
 * coefficients of its {@code k_sin.c} and {@code k_cos.c}), within an ulp or two of the true values
 * for the angles a body has (|a| ≤ π, as the engine keeps them; larger ones lose a little
 * accuracy, not determinism).
 */
final class Rotation {

    // fdlibm k_sin.c
    private static final double S1 = -1.66666666666666324348e-01;
    private static final double S2 = 8.33333333332248946124e-03;
    private static final double S3 = -1.98412698298579493134e-04;
    private static final double S4 = 2.75573137070700676789e-06;
    private static final double S5 = -2.50507602534068634195e-08;
    private static final double S6 = 1.58969099521155010221e-10;
    // fdlibm k_cos.c
    private static final double C1 = 4.16666666666666019037e-02;
    private static final double C2 = -1.38888888888741095749e-03;
    private static final double C3 = 2.48015872894767294178e-05;
    private static final double C4 = -2.75573143513906633035e-07;
    private static final double C5 = 2.08757232129817482790e-09;
    private static final double C6 = -1.13596475577881948265e-11;
    // π/2 in two parts (fdlibm e_rem_pio2.c's pio2_1 and pio2_1t) and 2/π
    private static final double PIO2_1 = 1.57079632673412561417e+00;
    private static final double PIO2_1T = 6.07710050650619224932e-11;
    private static final double INV_PIO2 = 6.36619772367581382433e-01;

    private Rotation() {
    }

    /**
     * @param a an angle, radians
     * @return its cosine
     */
    static double cos(double a) {
        int q = quadrant(a);
        double r = reduce(a, q);
        return switch (q & 3) {
            case 0 -> kernelCos(r);
            case 1 -> -kernelSin(r);
            case 2 -> -kernelCos(r);
            default -> kernelSin(r);
        };
    }

    /**
     * @param a an angle, radians
     * @return its sine
     */
    static double sin(double a) {
        int q = quadrant(a);
        double r = reduce(a, q);
        return switch (q & 3) {
            case 0 -> kernelSin(r);
            case 1 -> kernelCos(r);
            case 2 -> -kernelSin(r);
            default -> -kernelCos(r);
        };
    }

    /** @return the nearest whole number of quarter turns */
    static int quadrant(double a) {
        return (int) Math.rint(a * INV_PIO2);
    }

    /** @return the angle less that many quarter turns, in about [-π/4, π/4] */
    static double reduce(double a, int q) {
        return (a - q * PIO2_1) - q * PIO2_1T;
    }

    static double kernelSin(double x) {
        double z = x * x;
        double v = z * x;
        double r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
        return x + v * (S1 + z * r);
    }

    static double kernelCos(double x) {
        double z = x * x;
        double r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
        double hz = 0.5 * z;
        double w = 1.0 - hz;
        return w + (((1.0 - w) - hz) + z * r);
    }
}
