/* core/phase.c: theta, principal steps, triangle charts and windings (see
 * glpgp/phase.h for the conventions). */
#include "glpgp/phase.h"
#include "glpgp/kinds.h"

#include <math.h>

double glpgp_theta(double re, double im)
{
    if (!isfinite(re) || !isfinite(im)) return 0.0;
    if (im == 0.0 && re >= 0.0) return 0.0; /* positive axis (either zero sign) and z = 0 */
    /* t <- arg(z) / 2 pi, folded from (-1/2, 1/2] into [0, 1) */
    double t = atan2(im, re) / (2.0 * GLPGP_PI);
    if (t < 0.0) t += 1.0;
    if (!(t < 1.0)) t = 0.0; /* -tiny + 1 rounds to 1 */
    return t;
}

double glpgp_phase_step(double d)
{
    if (!isfinite(d)) return 0.0;
    /* d - round-half-up(d): [-1/2, 1/2) */
    return d - floor(d + 0.5);
}

void glpgp_phase_chart(const double th[3], double c[3])
{
    /* c_0 = theta_0;  c_j = c_0 + step(theta_j - theta_0) */
    c[0] = th[0];
    c[1] = th[0] + glpgp_phase_step(th[1] - th[0]);
    c[2] = th[0] + glpgp_phase_step(th[2] - th[0]);
}

int glpgp_phase_winding(const double th[3])
{
    /* w = step(t1 - t0) + step(t2 - t1) + step(t0 - t2): an integer up to rounding */
    double w = glpgp_phase_step(th[1] - th[0]) + glpgp_phase_step(th[2] - th[1]) +
               glpgp_phase_step(th[0] - th[2]);
    int k = (int)lround(w);
    return k > 1 ? 1 : k < -1 ? -1 : k;
}

int glpgp_phase_winding_z(const double *z, int a, int b, int c)
{
    double th[3] = {glpgp_theta(z[2 * a], z[2 * a + 1]), glpgp_theta(z[2 * b], z[2 * b + 1]),
                    glpgp_theta(z[2 * c], z[2 * c + 1])};
    return glpgp_phase_winding(th);
}
