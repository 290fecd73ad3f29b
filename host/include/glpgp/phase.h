/* glpgp/phase.h: the one phase module. Every caller that turns oscillator
 * values into phases (result writers, the rasteriser, quad extraction, the
 * singularity count) goes through these functions, so they agree at the edge
 * cases:
 *   - theta(z) = arg(z) / 2 pi in [0, 1); exactly 0 on the positive real axis
 *     (also for Im z = -0), for z = 0 and for non-finite z;
 *   - the principal step d -> d - floor(d + 1/2) lies in [-1/2, 1/2): a step
 *     of exactly +1/2 is taken as -1/2;
 *   - the chart of a triangle unwraps its corners relative to corner 0:
 *     c_0 = theta_0, c_j = c_0 + step(theta_j - theta_0);
 *   - the winding of a triangle is the sum of the principal steps around it
 *     (0->1, 1->2, 2->0), an integer (rounded).
 * Layer: core. */
#ifndef GLPGP_PHASE_H
#define GLPGP_PHASE_H

#ifdef __cplusplus
extern "C" {
#endif

/* theta = arg(re + i im) / 2 pi in [0, 1) (see above for the edge cases). */
double glpgp_theta(double re, double im);

/* Principal value of a phase difference d (in periods): d - floor(d + 1/2),
 * in [-1/2, 1/2). Non-finite d gives 0. */
double glpgp_phase_step(double d);

/* Unwrapped phases c[0..2] of a triangle with corner phases th[0..2]. */
void glpgp_phase_chart(const double th[3], double c[3]);

/* Winding of the corner phases th[0..2] (counter-clockwise corners): the sum
 * of the three principal steps, rounded: -1, 0 or +1 for any input. */
int glpgp_phase_winding(const double th[3]);

/* Winding of z (2 doubles per vertex) around triangle (a, b, c). */
int glpgp_phase_winding_z(const double *z, int a, int b, int c);

#ifdef __cplusplus
}
#endif

#endif
