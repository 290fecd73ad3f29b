/* amg_rows.h: the per-row / per-block arithmetic of the aggregation multigrid
 * preconditioner (ops amg_* of glpgp/backend.h), written so that it compiles
 * both as C11 (the reference backend, backends/reference_amg.c) and as
 * OpenCL C (phase 2: move this file next to kernels/element.h and embed it):
 * plain double arithmetic on values and private arrays only, no host types.
 *
 * Conventions: a 2x2 block a[4] is row-major [[a0, a1], [a2, a3]]; a complex
 * prolongation weight c = (cr, ci) acts as the block P = [[cr, -ci], [ci, cr]]
 * (multiplication by the complex number cr + i ci), so P^T = [[cr, ci],
 * [-ci, cr]] (multiplication by its conjugate). */
#ifndef GLPGP_AMG_ROWS_H
#define GLPGP_AMG_ROWS_H

#ifdef __OPENCL_VERSION__
#define GLPGP_AMG_FN inline
#else
#include <math.h>
#define GLPGP_AMG_FN static inline
#endif

/* acc += P_i^T A P_j for the complex weights (ir, ii) and (jr, ji):
 *   T = A P_j,  acc += P_i^T T  (one Galerkin contribution of a fine block). */
GLPGP_AMG_FN void glpgp_amg_ptap(double ir, double ii, const double *a, double jr, double ji,
                                 double *acc)
{
    const double t0 = a[0] * jr + a[1] * ji, t1 = -a[0] * ji + a[1] * jr;
    const double t2 = a[2] * jr + a[3] * ji, t3 = -a[2] * ji + a[3] * jr;
    acc[0] += ir * t0 + ii * t2;
    acc[1] += ir * t1 + ii * t3;
    acc[2] += -ii * t0 + ir * t2;
    acc[3] += -ii * t1 + ir * t3;
}

/* acc += P_i^T t  (restriction of one fine 2-vector t = (t0, t1) by the
 * weight (cr, ci): multiplication by the conjugate). */
GLPGP_AMG_FN void glpgp_amg_restrict_add(double cr, double ci, double t0, double t1, double *acc)
{
    acc[0] += cr * t0 + ci * t1;
    acc[1] += -ci * t0 + cr * t1;
}

/* x += P_i e  (prolongation of the coarse 2-vector e = (e0, e1)). */
GLPGP_AMG_FN void glpgp_amg_prolong_add(double cr, double ci, double e0, double e1, double *x)
{
    x[0] += cr * e0 - ci * e1;
    x[1] += ci * e0 + cr * e1;
}

/* One smoother row: y = x + Minv (r - ax), Minv the row's 2x2 block. */
GLPGP_AMG_FN void glpgp_amg_smooth_row(const double *minv, double r0, double r1, double ax0,
                                       double ax1, double x0, double x1, double *y)
{
    const double t0 = r0 - ax0, t1 = r1 - ax1;
    y[0] = x0 + minv[0] * t0 + minv[1] * t1;
    y[1] = x1 + minv[2] * t0 + minv[3] * t1;
}

/* Spectral norm ||a||_2 of a 2x2 block: a acts on u = x + iy as
 * u -> c u + d conj(u) with c = ((a0 + a3) + i (a2 - a1)) / 2 and
 * d = ((a0 - a3) + i (a1 + a2)) / 2, so ||a||_2 = |c| + |d|. */
GLPGP_AMG_FN double glpgp_amg_norm2(const double *a)
{
    const double cr = a[0] + a[3], ci = a[2] - a[1], dr = a[0] - a[3], di = a[1] + a[2];
    return 0.5 * (sqrt(cr * cr + ci * ci) + sqrt(dr * dr + di * di));
}

/* o <- w times the inverse of the l1 block diagonal  d + s I  (d: the
 * diagonal block, s = sum of the off-diagonal blocks' spectral norms);
 * o <- 0 when singular or not finite (that node is then left alone by the
 * smoother). */
GLPGP_AMG_FN void glpgp_amg_l1_inverse(const double *d, double s, double w, double *o)
{
    const double a0 = d[0] + s, a1 = d[1], a2 = d[2], a3 = d[3] + s;
    const double det = a0 * a3 - a1 * a2;
    const double i = w / det;
    if (det == 0.0 || !isfinite(i) || !isfinite(a0 + a1 + a2 + a3)) {
        o[0] = o[1] = o[2] = o[3] = 0.0;
        return;
    }
    o[0] = a3 * i;
    o[1] = -a1 * i;
    o[2] = -a2 * i;
    o[3] = a0 * i;
}

/* A coefficient from the scalar registers: sign * num / den, 0 when den is 0
 * or the ratio is not finite. */
GLPGP_AMG_FN double glpgp_amg_ratio(double sign, double num, double den)
{
    const double c = sign * (num / den);
    return (den != 0.0 && isfinite(c)) ? c : 0.0;
}

/* The K-cycle's two-step Krylov combination e = c[0] v + c[1] d (Notay and
 * Vassilevski's recursive Krylov cycle), from rho1 = v.A v, alpha1 = v.r,
 * beta = d.A d, gamma = d.A v, alpha2 = d.r2 (r2 = r - (alpha1/rho1) A v):
 *   rho2 = beta - gamma^2 / rho1,
 *   c[0] = alpha1/rho1 - gamma alpha2 / (rho1 rho2),  c[1] = alpha2 / rho2;
 * when rho2 <= 1e-12 |beta| (d adds nothing new) or a coefficient is not
 * finite: c = (alpha1/rho1, 0); when rho1 is 0: c = (0, 0). */
GLPGP_AMG_FN void glpgp_amg_kcoef(double rho1, double alpha1, double beta, double gamma,
                                  double alpha2, double *c)
{
    const double c0 = glpgp_amg_ratio(1.0, alpha1, rho1);
    c[0] = c0;
    c[1] = 0.0;
    if (c0 == 0.0) return;
    const double rho2 = beta - gamma * gamma / rho1;
    if (!(fabs(rho2) > 1e-12 * fabs(beta))) return;
    const double d0 = alpha1 / rho1 - gamma * alpha2 / (rho1 * rho2), d1 = alpha2 / rho2;
    if (!isfinite(d0) || !isfinite(d1)) return;
    c[0] = d0;
    c[1] = d1;
}

#endif
