/* newton_rows.h: the per-vertex arithmetic of the Newton driver's trial
 * points (the trust region's x (+) a d, solver/newton.c), written once for
 * every twin like rows.h: the OpenCL kernel glpgp_trial_point
 * (kernels/backend_newton.cl), the reference and PETSc backends' loops
 * (host/backends/reference.c, petsc.c) and the driver's host fallback call
 * the same functions, so all store the same bits (no fused multiply-add:
 * FP_CONTRACT OFF in the program, -ffp-contract=off on the C side).
 *
 * sin and cos are this file's own (glpgp_sincos): the OpenCL built-ins and
 * the C library round differently in the last bit, and a trial point must
 * be the same on every backend.
 *
 * Compiled as C11 and as OpenCL C (embedded after element.h, rows.h,
 * amg_rows.h; see kernels/embed.cmake). */
#ifndef GLPGP_NEWTON_ROWS_H
#define GLPGP_NEWTON_ROWS_H

#ifndef __OPENCL_VERSION__
#include <math.h>
#include "rows.h" /* GLPGP_GLOBAL, GLPGP_FN */
#endif

/* *s <- sin x, *c <- cos x to about 1 ulp for |x| below 8e5 (and bounded in
 * [-1, 1] for any finite x; NaN for a non-finite x): x = k pi/2 + r,
 * |r| <= pi/4, by pi/2 in three parts of 33, 33 and 53 bits (k pi/2 exact
 * for |k| < 2^20), then the Taylor polynomials of sin and cos on r (degree
 * 17 and 18: truncation below 1e-19) in Horner form, and the quadrant. */
GLPGP_FN void glpgp_sincos(double x, double *s, double *c)
{
    if (!isfinite(x)) {
        *s = *c = x - x; /* NaN */
        return;
    }
    if (!(fabs(x) < 1e15)) { /* k would not be an integer of a double: no quadrant */
        *s = 0.0;
        *c = 1.0;
        return;
    }
    const double k = rint(x * 0.63661977236758134308);
    const double r = ((x - k * 0x1.921fb54400000p+0) - k * 0x1.0b4611a600000p-34) - k * 0x1.3198a2e037073p-69;
    const double r2 = r * r;
    const double ps = r + r * r2 *
                              (-0.16666666666666666 +
                               r2 * (0.0083333333333333332 +
                                     r2 * (-0.00019841269841269841 +
                                           r2 * (2.7557319223985893e-06 +
                                                 r2 * (-2.505210838544172e-08 +
                                                       r2 * (1.6059043836821613e-10 +
                                                             r2 * (-7.6471637318198164e-13 +
                                                                   r2 * 2.8114572543455206e-15)))))));
    const double pc = 1.0 - 0.5 * r2 +
                      r2 * r2 *
                          (0.041666666666666664 +
                           r2 * (-0.0013888888888888889 +
                                 r2 * (2.4801587301587302e-05 +
                                       r2 * (-2.7557319223985888e-07 +
                                             r2 * (2.08767569878681e-09 +
                                                   r2 * (-1.1470745597729725e-11 +
                                                         r2 * (4.7794773323873853e-14 +
                                                               r2 * -1.5619206968586225e-16)))))));
    const int q = (int)(k - 4.0 * floor(0.25 * k)); /* k mod 4, exact */
    *s = q == 0 ? ps : q == 1 ? pc : q == 2 ? -ps : -pc;
    *c = q == 0 ? pc : q == 1 ? -ps : q == 2 ? -pc : ps;
}

/* The trial point of one vertex, z = (zr, zi), step a (dr, di) = a d_i:
 * straight z + a d where |z| <= r1 / 2 (vortex cores: the phase is
 * undefined), polar z (1 + Re w) e^{i Im w}, w = a d / z, where |z| >= r1 (a
 * phase rotation stays a rotation), blended linearly in |z| between; the
 * straight point also where 1 + Re w <= 0. Agrees with z + a d to first
 * order in d. r1 > 0. */
GLPGP_FN void glpgp_polar_point(double zr, double zi, double dr, double di, double r1, double *xr, double *xi)
{
    const double r0 = 0.5 * r1;
    const double m2 = zr * zr + zi * zi, m = sqrt(m2);
    double pr = zr + dr, py = zi + di; /* straight: z + a d */
    const double t = m >= r1 ? 1.0 : m <= r0 ? 0.0 : (m - r0) / (r1 - r0);
    if (t > 0.0) {
        /* w = a d / z = a d conj(z) / |z|^2;  polar: z (1 + Re w) e^{i Im w} */
        const double wr = (dr * zr + di * zi) / m2, wi = (di * zr - dr * zi) / m2;
        const double amp = 1.0 + wr;
        if (amp > 0.0) {
            double sn, cs;
            glpgp_sincos(wi, &sn, &cs);
            const double qr = amp * (zr * cs - zi * sn), qi = amp * (zr * sn + zi * cs);
            pr = t * qr + (1.0 - t) * pr;
            py = t * qi + (1.0 - t) * py;
        }
    }
    *xr = pr;
    *xi = py;
}

/* Vertex i of xt <- x (+) a d (glpgp_polar_point). */
GLPGP_FN void glpgp_row_trial_point(int i, GLPGP_GLOBAL const double *x, GLPGP_GLOBAL const double *d, double a,
                                    double r1, GLPGP_GLOBAL double *xt)
{
    double xr, xi;
    glpgp_polar_point(x[2 * i], x[2 * i + 1], a * d[2 * i], a * d[2 * i + 1], r1, &xr, &xi);
    xt[2 * i] = xr;
    xt[2 * i + 1] = xi;
}

#endif
