/* amg_rows.h: the per-block, per-row, per-aggregate and per-entry arithmetic
 * of the aggregation multigrid preconditioner (ops amg_* of glpgp/backend.h),
 * written once and shared by both twins, like kernels/rows.h:
 *   - the OpenCL kernels (kernels/backend_multigrid.cl) loop over their index range
 *     [lo, hi) calling these functions;
 *   - the C reference backend (host/backends/reference_amg.c) loops over all
 *     indices calling the same functions.
 * Every value stored per row, aggregate or entry is therefore bit-identical
 * on both sides (same operations in the same order, no fused multiply-add:
 * FP_CONTRACT OFF in the program, -ffp-contract=off for the backends layer;
 * sqrt and division are correctly rounded in OpenCL C for double). Only the
 * dot products differ, in the order of the final sum over rows
 * (per-work-item partials + finalize against one sequential sum).
 *
 * Compiled as C11 (it includes rows.h, hence element.h) and as OpenCL C
 * (embedded after glpgp/kinds.h, element.h and rows.h, see kernels/embed.cmake).
 * Arrays carry GLPGP_GLOBAL (__global in OpenCL C); private values and small
 * private arrays are plain.
 *
 * Conventions: a 2x2 block a[4] is row-major [[a0, a1], [a2, a3]]; a complex
 * prolongation weight c = (cr, ci) acts as the block P = [[cr, -ci], [ci, cr]]
 * (multiplication by the complex number cr + i ci), so P^T = [[cr, ci],
 * [-ci, cr]] (multiplication by its conjugate). Level layout: 2x2-block CSR
 * (rowptr, col, diag), aggregates agg / aptr / amem, Galerkin map gptr / gsrc,
 * srow[k] = row of block slot k (glpgp/backend.h, glpgp_amg_level). */
#ifndef GLPGP_AMG_ROWS_H
#define GLPGP_AMG_ROWS_H

#ifndef __OPENCL_VERSION__
#include <math.h>
#include "rows.h" /* GLPGP_GLOBAL, GLPGP_FN, glpgp_row_spmv */
#endif

/* Register layout of glpgp/backend.h (GLPGP_AMG_KSLOT, GLPGP_AMG_MAX_LEVELS;
 * host/backends/opencl.c checks that they agree). */
#define GLPGP_AMG_ROWS_KSLOT(l) (8 + 8 * (l))
#define GLPGP_AMG_ROWS_MAX_LEVELS 24

/* Table of the levels that the fused coarse-correction kernel
 * (glpgp_amg_bottom in backend_multigrid.cl) runs: one row of
 * GLPGP_AMG_BT_COUNT ints per level, offsets into the packed int array
 * (_ROWPTR .. _AMEM, in ints) and the packed double array (_VAL .. _WD, in
 * doubles); -1 where a level has no such array (the coarsest: no transfer,
 * no smoother, no K-cycle vectors). */
enum glpgp_amg_bt {
    GLPGP_AMG_BT_N = 0, /* nodes */
    GLPGP_AMG_BT_NC,    /* nodes of the next level (0 on the coarsest) */
    GLPGP_AMG_BT_K,     /* 1: the coarse correction of this level is a K-cycle */
    GLPGP_AMG_BT_ROWPTR,
    GLPGP_AMG_BT_COL,
    GLPGP_AMG_BT_DIAG,
    GLPGP_AMG_BT_AGG,
    GLPGP_AMG_BT_APTR,
    GLPGP_AMG_BT_AMEM,
    GLPGP_AMG_BT_VAL,
    GLPGP_AMG_BT_MINV,
    GLPGP_AMG_BT_C,
    GLPGP_AMG_BT_B,   /* right-hand side of the level's coarse correction */
    GLPGP_AMG_BT_E,   /* its result */
    GLPGP_AMG_BT_TMP, /* smoother ping-pong */
    GLPGP_AMG_BT_V,   /* K-cycle vectors */
    GLPGP_AMG_BT_W,
    GLPGP_AMG_BT_R2,
    GLPGP_AMG_BT_D,
    GLPGP_AMG_BT_WD,
    GLPGP_AMG_BT_COUNT
};

/* ---- per block ------------------------------------------------------------ */

/* acc += P_i^T A P_j for the complex weights (ir, ii) and (jr, ji):
 *   T = A P_j,  acc += P_i^T T  (one Galerkin contribution of a fine block). */
GLPGP_FN void glpgp_amg_ptap(double ir, double ii, const double *a, double jr, double ji,
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
GLPGP_FN void glpgp_amg_restrict_add(double cr, double ci, double t0, double t1, double *acc)
{
    acc[0] += cr * t0 + ci * t1;
    acc[1] += -ci * t0 + cr * t1;
}

/* x += P_i e  (prolongation of the coarse 2-vector e = (e0, e1)). */
GLPGP_FN void glpgp_amg_prolong_add(double cr, double ci, double e0, double e1, double *x)
{
    x[0] += cr * e0 - ci * e1;
    x[1] += ci * e0 + cr * e1;
}

/* One smoother row: y = x + Minv (r - ax), Minv the row's 2x2 block. */
GLPGP_FN void glpgp_amg_smooth_row(const double *minv, double r0, double r1, double ax0,
                                   double ax1, double x0, double x1, double *y)
{
    const double t0 = r0 - ax0, t1 = r1 - ax1;
    y[0] = x0 + minv[0] * t0 + minv[1] * t1;
    y[1] = x1 + minv[2] * t0 + minv[3] * t1;
}

/* Spectral norm ||a||_2 of a 2x2 block: a acts on u = x + iy as
 * u -> c u + d conj(u) with c = ((a0 + a3) + i (a2 - a1)) / 2 and
 * d = ((a0 - a3) + i (a1 + a2)) / 2, so ||a||_2 = |c| + |d|. */
GLPGP_FN double glpgp_amg_norm2(const double *a)
{
    const double cr = a[0] + a[3], ci = a[2] - a[1], dr = a[0] - a[3], di = a[1] + a[2];
    return 0.5 * (sqrt(cr * cr + ci * ci) + sqrt(dr * dr + di * di));
}

/* o <- w times the inverse of the l1 block diagonal  d + s I  (d: the
 * diagonal block, s = sum of the off-diagonal blocks' spectral norms);
 * o <- 0 when singular or not finite (that node is then left alone by the
 * smoother). */
GLPGP_FN void glpgp_amg_l1_inverse(const double *d, double s, double w, double *o)
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
GLPGP_FN double glpgp_amg_ratio(double sign, double num, double den)
{
    const double c = sign * (num / den);
    return (den != 0.0 && isfinite(c)) ? c : 0.0;
}

/* The coefficient (num, den, sign) of glpgp/backend.h's glpgp_amg_coef from
 * the registers t: sign * t[num] / t[den] (glpgp_amg_ratio); num < 0: sign. */
GLPGP_FN double glpgp_amg_coef_value(GLPGP_GLOBAL const double *t, int num, int den, double sign)
{
    return num < 0 ? sign : glpgp_amg_ratio(sign, t[num], t[den]);
}

/* The K-cycle's two-step Krylov combination e = c[0] v + c[1] d (Notay and
 * Vassilevski's recursive Krylov cycle), from rho1 = v.A v, alpha1 = v.r,
 * beta = d.A d, gamma = d.A v, alpha2 = d.r2 (r2 = r - (alpha1/rho1) A v):
 *   rho2 = beta - gamma^2 / rho1,
 *   c[0] = alpha1/rho1 - gamma alpha2 / (rho1 rho2),  c[1] = alpha2 / rho2;
 * when rho2 <= 1e-12 |beta| (d adds nothing new) or a coefficient is not
 * finite: c = (alpha1/rho1, 0); when rho1 is 0: c = (0, 0). */
GLPGP_FN void glpgp_amg_kcoef(double rho1, double alpha1, double beta, double gamma,
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

/* The block of slot k into a private array. */
GLPGP_FN void glpgp_amg_load_block(GLPGP_GLOBAL const double *A, long k, double *a)
{
    a[0] = A[4 * k];
    a[1] = A[4 * k + 1];
    a[2] = A[4 * k + 2];
    a[3] = A[4 * k + 3];
}

/* ---- per aggregate (hierarchy values) ------------------------------------- */

/* Frame of node i: f_i = a_i frame_i  (a_i = amp[i] when has_amp, else 1;
 * frame_i = (fr[2i], fr[2i+1]) when has_frame, else 1); 0 when has_dir and
 * dir[i] (a Dirichlet vertex of level 0: on no coarse level). */
GLPGP_FN void glpgp_amg_frame(int i, int has_amp, GLPGP_GLOBAL const double *amp, int has_frame,
                              GLPGP_GLOBAL const double *fr, int has_dir, GLPGP_GLOBAL const unsigned char *dir,
                              double *fx, double *fy)
{
    const double am = has_dir && dir[i] ? 0.0 : has_amp ? amp[i] : 1.0;
    *fx = has_frame ? am * fr[2 * i] : am;
    *fy = has_frame ? am * fr[2 * i + 1] : 0.0;
}

/* Aggregate J of level l (members amem[aptr[J] .. aptr[J+1])):
 *   s_J = sqrt(sum_{i in J} |f_i|^2);  amp_next[J] <- s_J;  c_i <- f_i / s_J;
 * J is dead (amp_next[J] <- 0, c_i <- 0) when s_J is 0 or not finite. */
GLPGP_FN void glpgp_amg_agg_weights(int J, GLPGP_GLOBAL const int *aptr, GLPGP_GLOBAL const int *amem,
                                    int has_amp, GLPGP_GLOBAL const double *amp, int has_frame,
                                    GLPGP_GLOBAL const double *fr, int has_dir,
                                    GLPGP_GLOBAL const unsigned char *dir, GLPGP_GLOBAL double *c,
                                    GLPGP_GLOBAL double *amp_next)
{
    double ss = 0.0, fx, fy;
    for (int p = aptr[J]; p < aptr[J + 1]; p++) {
        glpgp_amg_frame(amem[p], has_amp, amp, has_frame, fr, has_dir, dir, &fx, &fy);
        ss += fx * fx + fy * fy;
    }
    const double s = sqrt(ss);
    const int dead = !(s > 0.0) || !isfinite(s);
    amp_next[J] = dead ? 0.0 : s;
    for (int p = aptr[J]; p < aptr[J + 1]; p++) {
        const int i = amem[p];
        glpgp_amg_frame(i, has_amp, amp, has_frame, fr, has_dir, dir, &fx, &fy);
        c[2 * i] = dead ? 0.0 : fx / s;
        c[2 * i + 1] = dead ? 0.0 : fy / s;
    }
}

/* Coarse block row I of A_{l+1} = P_l^T A_l P_l (gather through the map):
 *   Ac[K] = sum_{q = gptr[K] .. gptr[K+1]} P_i^T A_l[k] P_j,  k = gsrc[q] = (i, j)
 *   (i = srow[k], j = col[k]; increasing k) for every slot K of row I, from 0;
 * a dead coarse node (amp_c[I] == 0) gets the identity diagonal block. */
GLPGP_FN void glpgp_amg_galerkin_row(int I, GLPGP_GLOBAL const int *crowptr, GLPGP_GLOBAL const int *cdiag,
                                     GLPGP_GLOBAL const int *gptr, GLPGP_GLOBAL const int *gsrc,
                                     GLPGP_GLOBAL const int *srow, GLPGP_GLOBAL const int *col,
                                     GLPGP_GLOBAL const double *c, GLPGP_GLOBAL const double *A,
                                     GLPGP_GLOBAL const double *amp_c, GLPGP_GLOBAL double *Ac)
{
    for (int K = crowptr[I]; K < crowptr[I + 1]; K++) {
        double acc[4] = {0.0, 0.0, 0.0, 0.0}, a[4];
        for (int q = gptr[K]; q < gptr[K + 1]; q++) {
            const int k = gsrc[q], i = srow[k], j = col[k];
            glpgp_amg_load_block(A, k, a);
            glpgp_amg_ptap(c[2 * i], c[2 * i + 1], a, c[2 * j], c[2 * j + 1], acc);
        }
        GLPGP_GLOBAL double *o = Ac + 4 * (long)K;
        o[0] = acc[0];
        o[1] = acc[1];
        o[2] = acc[2];
        o[3] = acc[3];
    }
    if (amp_c[I] == 0.0) {
        GLPGP_GLOBAL double *d = Ac + 4 * (long)cdiag[I];
        d[0] = 1.0;
        d[1] = 0.0;
        d[2] = 0.0;
        d[3] = 1.0;
    }
}

/* ---- per row --------------------------------------------------------------- */

/* Smoother row i: minv_i <- w (A_ii + (sum_{k != diag} ||A_k||_2) I)^-1
 * (glpgp_amg_l1_inverse; the norms summed in row order). */
GLPGP_FN void glpgp_amg_l1_row(int i, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *diag,
                               GLPGP_GLOBAL const double *A, double w, GLPGP_GLOBAL double *minv)
{
    double s = 0.0, a[4], o[4];
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++)
        if (k != diag[i]) {
            glpgp_amg_load_block(A, k, a);
            s += glpgp_amg_norm2(a);
        }
    glpgp_amg_load_block(A, diag[i], a);
    glpgp_amg_l1_inverse(a, s, w, o);
    GLPGP_GLOBAL double *m = minv + 4 * (long)i;
    m[0] = o[0];
    m[1] = o[1];
    m[2] = o[2];
    m[3] = o[3];
}

/* Smoother row i:  y_i <- x_i + M_i^-1 (r_i - (A x)_i)  (has_x = 0: x = 0,
 * y_i <- M_i^-1 r_i, x not read). y must not be x. */
GLPGP_FN void glpgp_amg_row_smooth(int i, int has_x, GLPGP_GLOBAL const int *rowptr,
                                   GLPGP_GLOBAL const int *col, GLPGP_GLOBAL const double *A,
                                   GLPGP_GLOBAL const double *minv, GLPGP_GLOBAL const double *r,
                                   GLPGP_GLOBAL const double *x, GLPGP_GLOBAL double *y)
{
    double ax0 = 0.0, ax1 = 0.0, x0 = 0.0, x1 = 0.0, m[4], o[2];
    if (has_x) {
        glpgp_row_spmv(i, rowptr, col, A, x, &ax0, &ax1);
        x0 = x[2 * i];
        x1 = x[2 * i + 1];
    }
    glpgp_amg_load_block(minv, i, m);
    glpgp_amg_smooth_row(m, r[2 * i], r[2 * i + 1], ax0, ax1, x0, x1, o);
    y[2 * i] = o[0];
    y[2 * i + 1] = o[1];
}

/* Residual of row i:  (t0, t1) <- r_i - (A x)_i  (has_x = 0: r_i), the
 * one form every restriction variant below uses. */
GLPGP_FN void glpgp_amg_row_resid(int i, int has_x, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                  GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *r,
                                  GLPGP_GLOBAL const double *x, double *t0, double *t1)
{
    *t0 = r[2 * i];
    *t1 = r[2 * i + 1];
    if (has_x) {
        double ax0, ax1;
        glpgp_row_spmv(i, rowptr, col, A, x, &ax0, &ax1);
        *t0 = r[2 * i] - ax0;
        *t1 = r[2 * i + 1] - ax1;
    }
}

/* Restriction of aggregate J:  rc_J <- sum_{i in J} P_i^T (r_i - (A x)_i)
 * (has_x = 0: P_i^T r_i), members in increasing order. */
GLPGP_FN void glpgp_amg_agg_restrict(int J, GLPGP_GLOBAL const int *aptr, GLPGP_GLOBAL const int *amem,
                                     GLPGP_GLOBAL const double *c, int has_x,
                                     GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                     GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *r,
                                     GLPGP_GLOBAL const double *x, GLPGP_GLOBAL double *rc)
{
    double acc[2] = {0.0, 0.0};
    for (int p = aptr[J]; p < aptr[J + 1]; p++) {
        const int i = amem[p];
        double t0, t1;
        glpgp_amg_row_resid(i, has_x, rowptr, col, A, r, x, &t0, &t1);
        glpgp_amg_restrict_add(c[2 * i], c[2 * i + 1], t0, t1, acc);
    }
    rc[2 * J] = acc[0];
    rc[2 * J + 1] = acc[1];
}

/* Residual row i:  t_i <- r_i - (A x)_i  (the first pass of the two-pass
 * restriction of a parallel device: rows in order, then the aggregates
 * gather t with has_x = 0 -- the sums of glpgp_amg_agg_restrict with
 * has_x = 1, bit for bit, reading 2 doubles per member instead of a row). */
GLPGP_FN void glpgp_amg_row_residual(int i, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                     GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *r,
                                     GLPGP_GLOBAL const double *x, GLPGP_GLOBAL double *t)
{
    double t0, t1;
    glpgp_amg_row_resid(i, 1, rowptr, col, A, r, x, &t0, &t1);
    t[2 * i] = t0;
    t[2 * i + 1] = t1;
}

/* Restriction in row order (the serial reference): for row i of aggregate
 * J = agg[i] >= 0,  rc_J += P_i^T (r_i - (A x)_i)  (has_x = 0: P_i^T r_i).
 * Called for i = 0, 1, ... after rc <- 0, every aggregate sums its members
 * in increasing order from 0: the sums of glpgp_amg_agg_restrict, bit for
 * bit, with the level's rows read in order (the gather reads them aggregate
 * by aggregate, scattered over the level: 46% of a reference solve on a
 * 107k-vertex CAD part). */
GLPGP_FN void glpgp_amg_row_restrict_scatter(int i, GLPGP_GLOBAL const int *agg, GLPGP_GLOBAL const double *c,
                                             int has_x, GLPGP_GLOBAL const int *rowptr,
                                             GLPGP_GLOBAL const int *col, GLPGP_GLOBAL const double *A,
                                             GLPGP_GLOBAL const double *r, GLPGP_GLOBAL const double *x,
                                             GLPGP_GLOBAL double *rc)
{
    const int J = agg[i];
    if (J < 0) return;
    double t0, t1;
    glpgp_amg_row_resid(i, has_x, rowptr, col, A, r, x, &t0, &t1);
    double acc[2];
    acc[0] = rc[2 * J];
    acc[1] = rc[2 * J + 1];
    glpgp_amg_restrict_add(c[2 * i], c[2 * i + 1], t0, t1, acc);
    rc[2 * J] = acc[0];
    rc[2 * J + 1] = acc[1];
}

/* ---- fused cycle steps (a level visit in fewer passes) ------------------- */

/* (y0, y1) <- M_j^-1 r_j: the pre-smoother from zero of row j, the bits
 * glpgp_amg_row_smooth (has_x = 0) stores. */
GLPGP_FN void glpgp_amg_presmooth_val(int j, GLPGP_GLOBAL const double *minv, GLPGP_GLOBAL const double *r, double *y0,
                                      double *y1)
{
    double m[4], o[2];
    glpgp_amg_load_block(minv, j, m);
    glpgp_amg_smooth_row(m, r[2 * j], r[2 * j + 1], 0.0, 0.0, 0.0, 0.0, o);
    *y0 = o[0];
    *y1 = o[1];
}

/* Row i of the pre-smoothed residual: y_i <- M_i^-1 r_i and (t0, t1) <-
 * r_i - (A y)_i, (A y)_i summed as glpgp_row_spmv with each y_j = M_j^-1 r_j
 * formed on the fly (glpgp_amg_presmooth_val): the bits of the pre-smoother
 * from zero followed by glpgp_amg_row_resid (has_x = 1), without writing y
 * and reading it back. */
GLPGP_FN void glpgp_amg_row_presmooth_resid(int i, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                            GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *minv,
                                            GLPGP_GLOBAL const double *r, GLPGP_GLOBAL double *y, double *t0,
                                            double *t1)
{
    double s0 = 0.0, s1 = 0.0, y0, y1;
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
        GLPGP_GLOBAL const double *blk = A + 4 * (long)k;
        glpgp_amg_presmooth_val(col[k], minv, r, &y0, &y1);
        s0 += blk[0] * y0 + blk[1] * y1;
        s1 += blk[2] * y0 + blk[3] * y1;
    }
    *t0 = r[2 * i] - s0;
    *t1 = r[2 * i + 1] - s1;
    glpgp_amg_presmooth_val(i, minv, r, &y0, &y1);
    y[2 * i] = y0;
    y[2 * i + 1] = y1;
}

/* Aggregate J of a visit's first half, fused: for its members i (increasing)
 * y_i <- M_i^-1 r_i and rc_J <- sum_i P_i^T (r_i - (A y)_i) -- the bits of
 * the pre-smoother from zero, then glpgp_amg_agg_restrict with x = y. */
GLPGP_FN void glpgp_amg_agg_presmooth_restrict(int J, GLPGP_GLOBAL const int *aptr, GLPGP_GLOBAL const int *amem,
                                               GLPGP_GLOBAL const double *c, GLPGP_GLOBAL const int *rowptr,
                                               GLPGP_GLOBAL const int *col, GLPGP_GLOBAL const double *A,
                                               GLPGP_GLOBAL const double *minv, GLPGP_GLOBAL const double *r,
                                               GLPGP_GLOBAL double *y, GLPGP_GLOBAL double *rc)
{
    double acc[2] = {0.0, 0.0};
    for (int p = aptr[J]; p < aptr[J + 1]; p++) {
        const int i = amem[p];
        double t0, t1;
        glpgp_amg_row_presmooth_resid(i, rowptr, col, A, minv, r, y, &t0, &t1);
        glpgp_amg_restrict_add(c[2 * i], c[2 * i + 1], t0, t1, acc);
    }
    rc[2 * J] = acc[0];
    rc[2 * J + 1] = acc[1];
}

/* (x0, x1) <- x_j + P_j ec_agg(j): the prolonged iterate of row j, the bits
 * glpgp_amg_row_prolong stores. */
GLPGP_FN void glpgp_amg_prolonged_val(int j, GLPGP_GLOBAL const int *agg, GLPGP_GLOBAL const double *c,
                                      GLPGP_GLOBAL const double *ec, GLPGP_GLOBAL const double *x, double *x0,
                                      double *x1)
{
    double v[2];
    v[0] = x[2 * j];
    v[1] = x[2 * j + 1];
    const int J = agg[j];
    if (J >= 0) glpgp_amg_prolong_add(c[2 * j], c[2 * j + 1], ec[2 * J], ec[2 * J + 1], v);
    *x0 = v[0];
    *x1 = v[1];
}

/* Row i of a visit's second half, fused: x' = x + P ec (prolongation),
 * y_i <- x'_i + M_i^-1 (r_i - (A x')_i) (the first post-smoothing sweep),
 * x'_j formed on the fly (glpgp_amg_prolonged_val): the bits of
 * glpgp_amg_row_prolong then glpgp_amg_row_smooth, without storing x'. */
GLPGP_FN void glpgp_amg_row_prolong_smooth(int i, GLPGP_GLOBAL const int *agg, GLPGP_GLOBAL const double *c,
                                           GLPGP_GLOBAL const double *ec, GLPGP_GLOBAL const int *rowptr,
                                           GLPGP_GLOBAL const int *col, GLPGP_GLOBAL const double *A,
                                           GLPGP_GLOBAL const double *minv, GLPGP_GLOBAL const double *r,
                                           GLPGP_GLOBAL const double *x, GLPGP_GLOBAL double *y)
{
    double s0 = 0.0, s1 = 0.0, x0, x1, m[4], o[2];
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
        GLPGP_GLOBAL const double *blk = A + 4 * (long)k;
        glpgp_amg_prolonged_val(col[k], agg, c, ec, x, &x0, &x1);
        s0 += blk[0] * x0 + blk[1] * x1;
        s1 += blk[2] * x0 + blk[3] * x1;
    }
    glpgp_amg_prolonged_val(i, agg, c, ec, x, &x0, &x1);
    glpgp_amg_load_block(minv, i, m);
    glpgp_amg_smooth_row(m, r[2 * i], r[2 * i + 1], s0, s1, x0, x1, o);
    y[2 * i] = o[0];
    y[2 * i + 1] = o[1];
}

/* Prolongation row i:  x_i <- x_i + P_i ec_agg(i)  (agg(i) < 0: unchanged). */
GLPGP_FN void glpgp_amg_row_prolong(int i, GLPGP_GLOBAL const int *agg, GLPGP_GLOBAL const double *c,
                                    GLPGP_GLOBAL const double *ec, GLPGP_GLOBAL double *x)
{
    const int J = agg[i];
    if (J < 0) return;
    double xi[2];
    xi[0] = x[2 * i];
    xi[1] = x[2 * i + 1];
    glpgp_amg_prolong_add(c[2 * i], c[2 * i + 1], ec[2 * J], ec[2 * J + 1], xi);
    x[2 * i] = xi[0];
    x[2 * i + 1] = xi[1];
}

/* Coarse solve row i (dense, order m):  x_i <- sum_j C_ij r_j, increasing j. */
GLPGP_FN void glpgp_amg_row_dense(int i, int m, GLPGP_GLOBAL const double *C, GLPGP_GLOBAL const double *r,
                                  GLPGP_GLOBAL double *x)
{
    GLPGP_GLOBAL const double *ci = C + (long)i * m;
    double s = 0.0;
    for (int j = 0; j < m; j++) s += ci[j] * r[j];
    x[i] = s;
}

/* ---- per entry ------------------------------------------------------------- */

/* Entry i of y <- p x + q y; a zero coefficient does not read its vector
 * (so 0 x + 0 y clears a y that holds NaN). */
GLPGP_FN void glpgp_amg_entry_axpby(long i, double p, GLPGP_GLOBAL const double *x, double q,
                                    GLPGP_GLOBAL double *y)
{
    double v = 0.0;
    if (p != 0.0) v += p * x[i];
    if (q != 0.0) v += q * y[i];
    y[i] = v;
}

/* Entry i of e <- c0 v + c1 d  (c1 = 0: d is not read). */
GLPGP_FN void glpgp_amg_entry_kcombine(long i, double c0, double c1, GLPGP_GLOBAL const double *v,
                                       GLPGP_GLOBAL const double *d, GLPGP_GLOBAL double *e)
{
    if (c1 == 0.0) e[i] = c0 * v[i];
    else e[i] = c0 * v[i] + c1 * d[i];
}

#endif
