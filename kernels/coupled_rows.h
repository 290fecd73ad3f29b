/* coupled_rows.h: the per-row bodies of the coupled cross-field solve
 * (issue 14, item 3; solver/coupled.c, docs/numerics.md "Coupled oscillators
 * across the cuts"), written once for the C reference backend and the
 * OpenCL kernels of kernels/backend_coupled.cl (compiled as C11 and as
 * OpenCL C, like rows.h).
 *
 * The system has 2 nv nodes, node 2i + s = oscillator s (0: u, 1: v) of
 * vertex i in that vertex's own representative frame, and 2 nt "virtual"
 * triangles: virtual triangle 2t + s is the frame oscillator s of mesh
 * triangle t, its corner a the node that carries it (tri[] of the virtual
 * mesh), with
 *   cconj[3t'+a] = 1: the frame value is the node's value conjugated,
 *                     X_frame = C X_node, C = diag(1, -1) (real pair);
 *   cfield[2(3t'+a)] the frame's unit field at that corner.
 * Pulled back through T = diag(C^{c_a}), every piece of the element and of
 * the penalty is that of rows.h in the frame:
 *   element block (a, b):   C^{c_a} [[re, -im], [im, re]] C^{c_b}
 *                         = [[re, -s_b im], [s_a im, s_a s_b re]],  s = 1 - 2c;
 *   penalty at the frame values z_a = (x_a, s_a y_a) (quadrature of |z|^2
 *   mixes the corners, so conjugation is applied per corner before it);
 *   gradient (gr, gi) -> (gr, s_a gi);  Hessian block (a, b) ->
 *   [[m00, s_b m01], [s_a m01, s_a s_b m11]].
 * Everything else (spmv, CG, multigrid) is the generic 2x2-block code. */
#ifndef GLPGP_COUPLED_ROWS_H
#define GLPGP_COUPLED_ROWS_H

#ifndef __OPENCL_VERSION__
#include "rows.h" /* OpenCL: rows.h precedes this file in the embedded program */
#endif

/* Frame values of triangle t (virtual) at x: (vr[a], vi[a]) = C^{c_a} x_node(a). */
GLPGP_FN void glpgp_ctri_vals(GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const unsigned char *cconj,
                              GLPGP_GLOBAL const double *v, int t, double *vr, double *vi)
{
    for (int a = 0; a < 3; a++) {
        const int i = tri[3 * t + a];
        vr[a] = v[2 * i];
        vi[a] = cconj[3 * t + a] ? -v[2 * i + 1] : v[2 * i + 1];
    }
}

/* Penalty energy of virtual triangle t at the frame values of x. */
GLPGP_FN double glpgp_ctri_pen_energy(int t, double inv4e2, GLPGP_GLOBAL const double *xy,
                                      GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const unsigned char *cconj,
                                      GLPGP_GLOBAL const double *x)
{
    double tx[3], ty[3], zr[3], zi[3];
    glpgp_tri_load(xy, tri, t, tx, ty);
    glpgp_ctri_vals(tri, cconj, x, t, zr, zi);
    return glpgp_pen_energy(glpgp_tri_area(tx, ty), inv4e2, zr, zi);
}

/* QUAD block row i of the coupled system (slot-map order, as glpgp_row_asm_quad):
 *   block(k) = sum_{(t,a,b) in contrib(k)} C^{c_a} [[re, -im], [im, re]] C^{c_b},
 * (re, im) the element entry of `kind` with the per-corner frame field cfield. */
GLPGP_FN void glpgp_crow_asm_quad(int i, int kind, double h, int sized, GLPGP_GLOBAL const double *sz,
                                  GLPGP_GLOBAL const double *xy, GLPGP_GLOBAL const int *tri,
                                  GLPGP_GLOBAL const unsigned char *cconj,
                                  GLPGP_GLOBAL const double *cfield, GLPGP_GLOBAL const int *rowptr,
                                  GLPGP_GLOBAL const int *cptr, GLPGP_GLOBAL const int *contrib,
                                  GLPGP_GLOBAL double *quad)
{
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
        double b0 = 0.0, b1 = 0.0, b2 = 0.0, b3 = 0.0;
        for (int c = cptr[k]; c < cptr[k + 1]; c++) {
            const int e = contrib[c], t = e / 9, a = (e % 9) / 3, b = e % 3;
            double x[3], y[3], wx[3], wy[3], er, ei;
            glpgp_tri_load(xy, tri, t, x, y);
            for (int q = 0; q < 3; q++) {
                wx[q] = cfield[2 * (3 * t + q)];
                wy[q] = cfield[2 * (3 * t + q) + 1];
            }
            if (sized) {
                double s[3], kt, ke[3], wt, we[3];
                glpgp_tri_scalars(tri, sz, t, s);
                glpgp_elem_scales(s, h, &kt, ke, &wt, we);
                glpgp_elem_entry_k(kind, x, y, wx, wy, kt, wt, ke, we, a, b, &er, &ei);
            } else {
                glpgp_elem_entry(kind, x, y, wx, wy, h, a, b, &er, &ei);
            }
            const double sa = cconj[3 * t + a] ? -1.0 : 1.0, sb = cconj[3 * t + b] ? -1.0 : 1.0;
            b0 += er;
            b1 += -(sb * ei);
            b2 += sa * ei;
            b3 += (sa * sb) * er;
        }
        GLPGP_GLOBAL double *blk = quad + 4 * (long)k;
        blk[0] = b0;
        blk[1] = b1;
        blk[2] = b2;
        blk[3] = b3;
    }
}

/* NEWTON block row i and DINV_i of the coupled system: glpgp_row_asm_newton
 * with the penalty Hessian blocks of each virtual triangle evaluated at its
 * frame values and pulled back, [[m00, s_b m01], [s_a m01, s_a s_b m11]].
 * Returns 1 when the diagonal block is singular (DINV_i = 0), else 0. */
GLPGP_FN int glpgp_crow_asm_newton(int i, int hess, double inv4e2, GLPGP_GLOBAL const double *xy,
                                   GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const unsigned char *cconj,
                                   GLPGP_GLOBAL const double *z, GLPGP_GLOBAL const int *rowptr,
                                   GLPGP_GLOBAL const int *col, GLPGP_GLOBAL const int *diag,
                                   GLPGP_GLOBAL const int *vptr, GLPGP_GLOBAL const int *vtri,
                                   GLPGP_GLOBAL const unsigned char *dir, GLPGP_GLOBAL const double *quad,
                                   GLPGP_GLOBAL double *newton, GLPGP_GLOBAL double *dinv)
{
    const int k0 = rowptr[i], k1 = rowptr[i + 1];
    glpgp_row_newton_zero(k0, k1, newton);
    if (!dir[i] && inv4e2 > 0.0) {
        for (int p = vptr[i]; p < vptr[i + 1]; p++) {
            const int t = vtri[p] / 3, a = vtri[p] % 3;
            double x[3], y[3], zr[3], zi[3], hm[9];
            glpgp_tri_load(xy, tri, t, x, y);
            glpgp_ctri_vals(tri, cconj, z, t, zr, zi);
            glpgp_pen_hess_row(hess, glpgp_tri_area(x, y), inv4e2, zr, zi, a, hm);
            const double sa = cconj[3 * t + a] ? -1.0 : 1.0;
            for (int b = 0; b < 3; b++) {
                const int j = tri[3 * t + b];
                if (dir[j]) continue;
                int k = k0;
                while (k < k1 && col[k] != j) k++;
                if (k == k1) continue;
                const double sb = cconj[3 * t + b] ? -1.0 : 1.0;
                GLPGP_GLOBAL double *blk = newton + 4 * (long)k;
                blk[0] += hm[3 * b];
                blk[1] += sb * hm[3 * b + 1];
                blk[2] += sa * hm[3 * b + 1];
                blk[3] += (sa * sb) * hm[3 * b + 2];
            }
        }
    }
    return glpgp_row_newton_finish(i, k0, k1, col, diag, dir, quad, newton, dinv);
}

/* Gradient row i of the coupled system: g_i <- (QUAD x)_i + sum over the
 * corners (t, a) of node i of C^{c_a} dP_t/dz_a (frame values); 0 when dir[i];
 * *e += x_i . (QUAD x)_i. */
GLPGP_FN void glpgp_crow_gradient(int i, double inv4e2, GLPGP_GLOBAL const double *xy,
                                  GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const unsigned char *cconj,
                                  GLPGP_GLOBAL const double *x, GLPGP_GLOBAL const int *rowptr,
                                  GLPGP_GLOBAL const int *col, GLPGP_GLOBAL const double *quad,
                                  GLPGP_GLOBAL const int *vptr, GLPGP_GLOBAL const int *vtri,
                                  GLPGP_GLOBAL const unsigned char *dir, GLPGP_GLOBAL double *g, double *e)
{
    double y0, y1;
    glpgp_row_spmv(i, rowptr, col, quad, x, &y0, &y1);
    glpgp_row_dot_acc(i, x, y0, y1, e);
    if (dir[i]) {
        y0 = 0.0;
        y1 = 0.0;
    } else if (inv4e2 > 0.0) {
        double sr = 0.0, si = 0.0;
        for (int p = vptr[i]; p < vptr[i + 1]; p++) {
            const int t = vtri[p] / 3, a = vtri[p] % 3;
            double tx[3], ty[3], zr[3], zi[3], er, ei;
            glpgp_tri_load(xy, tri, t, tx, ty);
            glpgp_ctri_vals(tri, cconj, x, t, zr, zi);
            glpgp_pen_grad(glpgp_tri_area(tx, ty), inv4e2, zr, zi, a, &er, &ei);
            sr += er;
            si += cconj[3 * t + a] ? -ei : ei;
        }
        y0 += sr;
        y1 += si;
    }
    g[2 * i] = y0;
    g[2 * i + 1] = y1;
}

#endif
