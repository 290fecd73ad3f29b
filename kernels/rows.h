/* rows.h: the per-row, per-entry and per-triangle bodies of every backend op
 * that has an OpenCL kernel, written once and shared by both twins:
 *   - the OpenCL kernels (kernels/backend_*.cl) loop over their index range
 *     [lo, hi) calling these functions;
 *   - the C reference backend (host/backends/reference.c) loops over all
 *     indices calling the same functions.
 * So a kernel and its reference twin cannot diverge: every value they store
 * per row is bit-identical. Only the reductions differ, in the order of the
 * final sum over rows / triangles (per-work-item partials, then
 * glpgp_finalize of backend_common.cl, against one sequential sum here).
 *
 * Compiled as C11 (reference.c includes it; it includes element.h) and as
 * OpenCL C (embedded after glpgp/kinds.h and element.h, see kernels/embed.cmake).
 * GLPGP_GLOBAL is the address space of the arrays: __global in OpenCL C, empty
 * in C. Accumulators and outputs of private values are plain pointers
 * (__private in OpenCL). Neither side contracts a*b + c into a fused
 * multiply-add: the OpenCL program starts with "#pragma OPENCL FP_CONTRACT OFF"
 * (host/backends/opencl.c) and the backends layer is compiled with
 * -ffp-contract=off (host/CMakeLists.txt).
 *
 * Layout (glpgp/system.h, glpgp/backend.h): vectors hold [Re, Im] per vertex;
 * matrices are 2x2-block CSR (rowptr, col; 4 doubles a block, row-major);
 * the slot map contrib[cptr[k] .. cptr[k+1]) lists the element entries
 * t*9 + a*3 + b summing into block k; vtri[vptr[i] .. vptr[i+1]) = t*3 + a
 * lists the corners that are vertex i. */
#ifndef GLPGP_ROWS_H
#define GLPGP_ROWS_H

#ifdef __OPENCL_VERSION__
#define GLPGP_GLOBAL __global
/* glpgp/kinds.h and element.h precede this file in the embedded program */
#else
#define GLPGP_GLOBAL
#include "element.h"
#endif

/* Scalar register of p.Ap (glpgp/backend.h: GLPGP_S_PQ; reference.c checks). */
#define GLPGP_ROWS_S_PQ 2

/* ---- triangles ------------------------------------------------------------ */

/* Corner coordinates of triangle t: (x[a], y[a]), a = 0..2. */
GLPGP_FN void glpgp_tri_load(GLPGP_GLOBAL const double *xy, GLPGP_GLOBAL const int *tri, int t,
                             double *x, double *y)
{
    for (int a = 0; a < 3; a++) {
        const int v = tri[3 * t + a];
        x[a] = xy[2 * v];
        y[a] = xy[2 * v + 1];
    }
}

/* Corner values (Re, Im) of the 2-per-vertex vector v on triangle t. */
GLPGP_FN void glpgp_tri_vals(GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const double *v, int t,
                             double *vr, double *vi)
{
    for (int a = 0; a < 3; a++) {
        const int i = tri[3 * t + a];
        vr[a] = v[2 * i];
        vi[a] = v[2 * i + 1];
    }
}

/* Penalty energy of triangle t at x:  P_t = A/(4 eps^2) sum_q w_q (|x_q|^2 - 1)^2. */
GLPGP_FN double glpgp_tri_pen_energy(int t, double inv4e2, GLPGP_GLOBAL const double *xy,
                                     GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const double *x)
{
    double tx[3], ty[3], zr[3], zi[3];
    glpgp_tri_load(xy, tri, t, tx, ty);
    glpgp_tri_vals(tri, x, t, zr, zi);
    return glpgp_pen_energy(glpgp_tri_area(tx, ty), inv4e2, zr, zi);
}

/* ---- block rows ----------------------------------------------------------- */

/* (A x)_i for block row i:  (*y0, *y1) = sum_k A_k x_col(k), k in row i. */
GLPGP_FN void glpgp_row_spmv(int i, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                             GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *x, double *y0,
                             double *y1)
{
    double s0 = 0.0, s1 = 0.0;
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
        GLPGP_GLOBAL const double *blk = A + 4 * (long)k;
        const int j = col[k];
        const double x0 = x[2 * j], x1 = x[2 * j + 1];
        s0 += blk[0] * x0 + blk[1] * x1;
        s1 += blk[2] * x0 + blk[3] * x1;
    }
    *y0 = s0;
    *y1 = s1;
}

/* *s += x_i . (y0, y1), the two terms in order (a row's share of x . y). */
GLPGP_FN void glpgp_row_dot_acc(int i, GLPGP_GLOBAL const double *x, double y0, double y1, double *s)
{
    *s += x[2 * i] * y0;
    *s += x[2 * i + 1] * y1;
}

/* y_i <- (A x)_i. */
GLPGP_FN void glpgp_row_spmv_store(int i, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                   GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *x,
                                   GLPGP_GLOBAL double *y)
{
    double y0, y1;
    glpgp_row_spmv(i, rowptr, col, A, x, &y0, &y1);
    y[2 * i] = y0;
    y[2 * i + 1] = y1;
}

/* q_i <- (A p)_i;  *s += p_i . q_i. */
GLPGP_FN void glpgp_row_spmv_dot(int i, GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                 GLPGP_GLOBAL const double *A, GLPGP_GLOBAL const double *p,
                                 GLPGP_GLOBAL double *q, double *s)
{
    double y0, y1;
    glpgp_row_spmv(i, rowptr, col, A, p, &y0, &y1);
    q[2 * i] = y0;
    q[2 * i + 1] = y1;
    glpgp_row_dot_acc(i, p, y0, y1, s);
}

/* ---- assembly ------------------------------------------------------------- */

/* Corner values s[a] of the 1-per-vertex array v on triangle t. */
GLPGP_FN void glpgp_tri_scalars(GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const double *v, int t, double *s)
{
    for (int a = 0; a < 3; a++) s[a] = v[tri[3 * t + a]];
}

/* QUAD block row i (gather through the slot map, in slot-map order):
 *   block(k) = sum_{(t,a,b) in contrib(k)} H_T(a,b),  H = re + i im  ->  [[re, -im], [im, re]]
 * for every slot k of row i; element kind `kind`, field w, target size h
 * (sized == 0), or the per-vertex sizes sz (sized != 0; glpgp_elem_scales). */
GLPGP_FN void glpgp_row_asm_quad(int i, int kind, double h, int sized, GLPGP_GLOBAL const double *sz,
                                 GLPGP_GLOBAL const double *xy, GLPGP_GLOBAL const int *tri,
                                 GLPGP_GLOBAL const double *w, GLPGP_GLOBAL const int *rowptr,
                                 GLPGP_GLOBAL const int *cptr, GLPGP_GLOBAL const int *contrib,
                                 GLPGP_GLOBAL double *quad)
{
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
        double re = 0.0, im = 0.0;
        for (int c = cptr[k]; c < cptr[k + 1]; c++) {
            const int e = contrib[c], t = e / 9, a = (e % 9) / 3, b = e % 3;
            double x[3], y[3], wx[3], wy[3], er, ei;
            glpgp_tri_load(xy, tri, t, x, y);
            glpgp_tri_vals(tri, w, t, wx, wy);
            if (sized) {
                double s[3], kt, ke[3], wt, we[3];
                glpgp_tri_scalars(tri, sz, t, s);
                glpgp_elem_scales(s, h, &kt, ke, &wt, we);
                glpgp_elem_entry_k(kind, x, y, wx, wy, kt, wt, ke, we, a, b, &er, &ei);
            } else {
                glpgp_elem_entry(kind, x, y, wx, wy, h, a, b, &er, &ei);
            }
            re += er;
            im += ei;
        }
        GLPGP_GLOBAL double *blk = quad + 4 * (long)k;
        blk[0] = re;
        blk[1] = -im;
        blk[2] = im;
        blk[3] = re;
    }
}

/* NEWTON_k <- 0 for the slots k0 .. k1 of a row (the penalty sums start at
 * 0, as m = 0.0 per slot). Shared by the plain and the coupled rows. */
GLPGP_FN void glpgp_row_newton_zero(int k0, int k1, GLPGP_GLOBAL double *newton)
{
    for (int k = k0; k < k1; k++) {
        GLPGP_GLOBAL double *blk = newton + 4 * (long)k;
        blk[0] = 0.0;
        blk[1] = 0.0;
        blk[2] = 0.0;
        blk[3] = 0.0;
    }
}

/* The end of a NEWTON row i (slots k0 .. k1, the penalty sums already in
 * newton): NEWTON_k <- QUAD_k + penalty sum, a Dirichlet row / column -> I
 * or 0; DINV_i <- the inverse of the diagonal block (0 and returns 1 when
 * singular). Shared by the plain and the coupled rows (coupled_rows.h). */
GLPGP_FN int glpgp_row_newton_finish(int i, int k0, int k1, GLPGP_GLOBAL const int *col,
                                     GLPGP_GLOBAL const int *diag, GLPGP_GLOBAL const unsigned char *dir,
                                     GLPGP_GLOBAL const double *quad, GLPGP_GLOBAL double *newton,
                                     GLPGP_GLOBAL double *dinv)
{
    /* NEWTON_k <- QUAD_k + penalty sum; Dirichlet row/column -> I or 0 */
    for (int k = k0; k < k1; k++) {
        const int j = col[k];
        GLPGP_GLOBAL double *blk = newton + 4 * (long)k;
        if (dir[i] || dir[j]) {
            const double d = (i == j) ? 1.0 : 0.0;
            blk[0] = d;
            blk[1] = 0.0;
            blk[2] = 0.0;
            blk[3] = d;
            continue;
        }
        GLPGP_GLOBAL const double *qb = quad + 4 * (long)k;
        blk[0] = qb[0] + blk[0];
        blk[1] = qb[1] + blk[1];
        blk[2] = qb[2] + blk[2];
        blk[3] = qb[3] + blk[3];
    }
    GLPGP_GLOBAL const double *d = newton + 4 * (long)diag[i];
    const double det = d[0] * d[3] - d[1] * d[2];
    GLPGP_GLOBAL double *o = dinv + 4 * (long)i;
    if (det == 0.0) {
        o[0] = 0.0;
        o[1] = 0.0;
        o[2] = 0.0;
        o[3] = 0.0;
        return 1;
    }
    o[0] = d[3] / det;
    o[1] = -d[1] / det;
    o[2] = -d[2] / det;
    o[3] = d[0] / det;
    return 0;
}

/* NEWTON block row i and DINV_i:
 *   NEWTON_k <- QUAD_k + sum_{(t,a,b) in contrib(k)} d2P_t/dX_a dX_b  (variant hess, weight
 *               inv4e2 = 1/(4 eps^2) at z; no penalty when inv4e2 <= 0), slot-map order;
 *   a block in a Dirichlet row or column (dir[i] or dir[j]) becomes I (diagonal) or 0;
 *   DINV_i <- [[d0, d1], [d2, d3]]^-1 = [[d3, -d1], [-d2, d0]] / (d0 d3 - d1 d2) of NEWTON's
 *             diagonal block (diag[i]).
 * Loop over the corners (t,a) of vertex i (vtri, increasing t*3 + a) rather than over
 * the slot map: each triangle is loaded and its quadrature values z_q and M_q are
 * evaluated once for its three blocks (a,0..2) (glpgp_pen_hess_row), not once per
 * block (9 times per triangle, 3 times per row). Each block (t,a,b) is added to the
 * slot k of column tri[3t+b] in increasing t*9 + a*3 + b, which is the slot-map order
 * (contrib lists increasing element entries), so every NEWTON value is bit for bit
 * what the per-slot sum gives. The row's NEWTON blocks are the accumulators.
 * Returns 1 (DINV_i set to 0) when that block is singular (det == 0), else 0. */
GLPGP_FN int glpgp_row_asm_newton(int i, int hess, double inv4e2, GLPGP_GLOBAL const double *xy,
                                  GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const double *z,
                                  GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                  GLPGP_GLOBAL const int *diag, GLPGP_GLOBAL const int *vptr,
                                  GLPGP_GLOBAL const int *vtri, GLPGP_GLOBAL const unsigned char *dir,
                                  GLPGP_GLOBAL const double *quad, GLPGP_GLOBAL double *newton,
                                  GLPGP_GLOBAL double *dinv)
{
    const int k0 = rowptr[i], k1 = rowptr[i + 1];
    glpgp_row_newton_zero(k0, k1, newton);
    if (!dir[i] && inv4e2 > 0.0) {
        /* NEWTON_k += d2P_t/dX_a dX_b for the corners (t,a) of i, b = 0..2 */
        for (int p = vptr[i]; p < vptr[i + 1]; p++) {
            const int t = vtri[p] / 3, a = vtri[p] % 3;
            double x[3], y[3], zr[3], zi[3], hm[9];
            glpgp_tri_load(xy, tri, t, x, y);
            glpgp_tri_vals(tri, z, t, zr, zi);
            glpgp_pen_hess_row(hess, glpgp_tri_area(x, y), inv4e2, zr, zi, a, hm);
            for (int b = 0; b < 3; b++) {
                const int j = tri[3 * t + b];
                if (dir[j]) continue; /* overwritten below */
                int k = k0;
                while (k < k1 && col[k] != j) k++;
                if (k == k1) continue; /* not in the pattern: cannot happen (pattern from tri) */
                GLPGP_GLOBAL double *blk = newton + 4 * (long)k;
                blk[0] += hm[3 * b];
                blk[1] += hm[3 * b + 1];
                blk[2] += hm[3 * b + 1];
                blk[3] += hm[3 * b + 2];
            }
        }
    }
    return glpgp_row_newton_finish(i, k0, k1, col, diag, dir, quad, newton, dinv);
}

/* ---- energy and gradient -------------------------------------------------- */

/* Penalty gradient at vertex i:  (*gr, *gi) = sum_{(t,a) in vtri(i)} dP_t/dX_a at x. */
GLPGP_FN void glpgp_vertex_pen_grad(int i, double inv4e2, GLPGP_GLOBAL const double *xy,
                                    GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const double *x,
                                    GLPGP_GLOBAL const int *vptr, GLPGP_GLOBAL const int *vtri,
                                    double *gr, double *gi)
{
    double sr = 0.0, si = 0.0;
    for (int p = vptr[i]; p < vptr[i + 1]; p++) {
        const int t = vtri[p] / 3, a = vtri[p] % 3;
        double tx[3], ty[3], zr[3], zi[3], er, ei;
        glpgp_tri_load(xy, tri, t, tx, ty);
        glpgp_tri_vals(tri, x, t, zr, zi);
        glpgp_pen_grad(glpgp_tri_area(tx, ty), inv4e2, zr, zi, a, &er, &ei);
        sr += er;
        si += ei;
    }
    *gr = sr;
    *gi = si;
}

/* Gradient row i:  g_i <- (QUAD x)_i + grad_i P(x)  (no penalty when inv4e2 <= 0;
 * 0 when dir[i]);  *e += x_i . (QUAD x)_i  (the row's share of x . QUAD x = 2 E). */
GLPGP_FN void glpgp_row_gradient(int i, double inv4e2, GLPGP_GLOBAL const double *xy,
                                 GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const double *x,
                                 GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *col,
                                 GLPGP_GLOBAL const double *quad, GLPGP_GLOBAL const int *vptr,
                                 GLPGP_GLOBAL const int *vtri, GLPGP_GLOBAL const unsigned char *dir,
                                 GLPGP_GLOBAL double *g, double *e)
{
    double y0, y1;
    glpgp_row_spmv(i, rowptr, col, quad, x, &y0, &y1);
    glpgp_row_dot_acc(i, x, y0, y1, e);
    if (dir[i]) {
        y0 = 0.0;
        y1 = 0.0;
    } else if (inv4e2 > 0.0) {
        double gr, gi;
        glpgp_vertex_pen_grad(i, inv4e2, xy, tri, x, vptr, vtri, &gr, &gi);
        y0 += gr;
        y1 += gi;
    }
    g[2 * i] = y0;
    g[2 * i + 1] = y1;
}

/* ---- vectors -------------------------------------------------------------- */

/* Entry i of y <- a x + c y. A zero coefficient drops its term without
 * reading the vector, so a NaN or Inf there does not leak (0 * NaN = NaN):
 *   a = 0: y_i <- c y_i;  c = 0: y_i <- a x_i;  both 0: y_i <- 0. */
GLPGP_FN void glpgp_entry_axpby(long i, double a, GLPGP_GLOBAL const double *x, double c,
                                GLPGP_GLOBAL double *y)
{
    if (a != 0.0 && c != 0.0) y[i] = a * x[i] + c * y[i];
    else if (a != 0.0) y[i] = a * x[i];
    else if (c != 0.0) y[i] = c * y[i];
    else y[i] = 0.0;
}

/* sum_{lo <= i < hi} x_i y_i, in increasing i. */
GLPGP_FN double glpgp_range_dot(long lo, long hi, GLPGP_GLOBAL const double *x,
                                GLPGP_GLOBAL const double *y)
{
    double s = 0.0;
    for (long i = lo; i < hi; i++) s += x[i] * y[i];
    return s;
}

/* ---- Jacobi-PCG ----------------------------------------------------------- */

/* Jacobi row i:  z_i <- DINV_i r_i;  *rz += r_i . z_i;  *rr += r_i . r_i. */
GLPGP_FN void glpgp_row_precond(int i, GLPGP_GLOBAL const double *dinv, GLPGP_GLOBAL const double *r,
                                GLPGP_GLOBAL double *z, double *rz, double *rr)
{
    GLPGP_GLOBAL const double *d = dinv + 4 * (long)i;
    const double r0 = r[2 * i], r1 = r[2 * i + 1];
    const double z0 = d[0] * r0 + d[1] * r1, z1 = d[2] * r0 + d[3] * r1;
    z[2 * i] = z0;
    z[2 * i + 1] = z1;
    *rz += r0 * z0 + r1 * z1;
    *rr += r0 * r0 + r1 * r1;
}

/* CG step length from the scalar registers:  alpha = s[rz] / s[PQ]  (r.z / p.Ap). */
GLPGP_FN double glpgp_cg_alpha(GLPGP_GLOBAL const double *s, int rz)
{
    return s[rz] / s[GLPGP_ROWS_S_PQ];
}

/* CG direction weight:  beta = s[rz_new] / s[rz]  ((r.z)_new / (r.z)_old). */
GLPGP_FN double glpgp_cg_beta(GLPGP_GLOBAL const double *s, int rz_new, int rz)
{
    return s[rz_new] / s[rz];
}

/* CG update row i:  x_i <- x_i + alpha p_i;  r_i <- r_i - alpha q_i;  then the
 * Jacobi row (z_i <- DINV_i r_i, *rz += r_i . z_i, *rr += r_i . r_i). */
GLPGP_FN void glpgp_row_cg_update(int i, double alpha, GLPGP_GLOBAL double *x, GLPGP_GLOBAL double *r,
                                  GLPGP_GLOBAL const double *p, GLPGP_GLOBAL const double *q,
                                  GLPGP_GLOBAL const double *dinv, GLPGP_GLOBAL double *z, double *rz,
                                  double *rr)
{
    x[2 * i] += alpha * p[2 * i];
    x[2 * i + 1] += alpha * p[2 * i + 1];
    r[2 * i] = r[2 * i] - alpha * q[2 * i];
    r[2 * i + 1] = r[2 * i + 1] - alpha * q[2 * i + 1];
    glpgp_row_precond(i, dinv, r, z, rz, rr);
}

/* CG direction entry i:  p_i <- z_i + beta p_i. */
GLPGP_FN void glpgp_entry_cg_direction(long i, double beta, GLPGP_GLOBAL double *p,
                                       GLPGP_GLOBAL const double *z)
{
    p[i] = z[i] + beta * p[i];
}

#endif
