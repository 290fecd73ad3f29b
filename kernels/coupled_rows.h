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
 * Surfaces (issue 28; solver/surface_solve.c, host/README.md "Surfaces")
 * add two optional per-triangle / per-corner arrays (NULL: the planar
 * arithmetic above, unchanged bit for bit):
 *   txy[6t' + 2a]: corner a of (virtual) triangle t' in the triangle's own
 *     plane, replacing the mesh's xy (a surface has no global plane);
 *   crot[2(3t'+a)]: a unit complex r_a = (cos, sin): the frame value is the
 *     node value, conjugated when cconj, then turned by r_a (the cross field
 *     w = u^4 of a vertex's frame enters triangle t's frame as
 *     exp(4 i phi) w). In real pairs T_a = R(r_a) C^{c_a}; every piece is
 *     pulled back through it:
 *   element block (a, b): the complex entry h becomes conj(r_a) h r_b, then
 *     the conjugation pattern above;
 *   penalty at the frame values r_a conj^{c_a}(z_a); gradient C^{c_a}
 *   R(r_a)^T g; Hessian block C^{c_a} R(r_a)^T M R(r_b) C^{c_b}.
 * Everything else (spmv, CG, multigrid) is the generic 2x2-block code. */
#ifndef GLPGP_COUPLED_ROWS_H
#define GLPGP_COUPLED_ROWS_H

#ifndef __OPENCL_VERSION__
#include "rows.h" /* OpenCL: rows.h precedes this file in the embedded program */
#endif

/* Corner coordinates of (virtual) triangle t: its own plane's (txy, a
 * surface) or the mesh's (glpgp_tri_load). */
GLPGP_FN void glpgp_ctri_load(GLPGP_GLOBAL const double *xy, GLPGP_GLOBAL const double *txy,
                              GLPGP_GLOBAL const int *tri, int t, double *x, double *y)
{
    if (txy) {
        for (int a = 0; a < 3; a++) {
            x[a] = txy[6 * t + 2 * a];
            y[a] = txy[6 * t + 2 * a + 1];
        }
    } else {
        glpgp_tri_load(xy, tri, t, x, y);
    }
}

/* Frame values of triangle t (virtual) at x: (vr[a], vi[a]) = R(r_a) C^{c_a} x_node(a)
 * (no turn when crot is NULL). */
GLPGP_FN void glpgp_ctri_vals(GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const unsigned char *cconj,
                              GLPGP_GLOBAL const double *crot, GLPGP_GLOBAL const double *v, int t, double *vr,
                              double *vi)
{
    for (int a = 0; a < 3; a++) {
        const int i = tri[3 * t + a];
        const double xr = v[2 * i], xi = cconj[3 * t + a] ? -v[2 * i + 1] : v[2 * i + 1];
        if (crot) {
            const double c = crot[2 * (3 * t + a)], s = crot[2 * (3 * t + a) + 1];
            vr[a] = c * xr - s * xi;
            vi[a] = s * xr + c * xi;
        } else {
            vr[a] = xr;
            vi[a] = xi;
        }
    }
}

/* Penalty energy of virtual triangle t at the frame values of x. */
GLPGP_FN double glpgp_ctri_pen_energy(int t, double inv4e2, GLPGP_GLOBAL const double *xy,
                                      GLPGP_GLOBAL const double *txy, GLPGP_GLOBAL const int *tri,
                                      GLPGP_GLOBAL const unsigned char *cconj, GLPGP_GLOBAL const double *crot,
                                      GLPGP_GLOBAL const double *x)
{
    double tx[3], ty[3], zr[3], zi[3];
    glpgp_ctri_load(xy, txy, tri, t, tx, ty);
    glpgp_ctri_vals(tri, cconj, crot, x, t, zr, zi);
    return glpgp_pen_energy(glpgp_tri_area(tx, ty), inv4e2, zr, zi);
}

/* The element entry (re, im) of corners (a, b) of virtual triangle t turned
 * by its corners' rotations: conj(r_a) (re + i im) r_b (crot NULL: as it is). */
GLPGP_FN void glpgp_ctri_turn_entry(GLPGP_GLOBAL const double *crot, int t, int a, int b, double *re, double *im)
{
    if (!crot) return;
    const double ca = crot[2 * (3 * t + a)], sa = crot[2 * (3 * t + a) + 1];
    const double cb = crot[2 * (3 * t + b)], sb = crot[2 * (3 * t + b) + 1];
    const double pr = ca * cb + sa * sb, pi = ca * sb - sa * cb; /* r_b conj(r_a) */
    const double er = *re, ei = *im;
    *re = er * pr - ei * pi;
    *im = er * pi + ei * pr;
}

/* QUAD block row i of the coupled system (slot-map order, as glpgp_row_asm_quad):
 *   block(k) = sum_{(t,a,b) in contrib(k)} C^{c_a} [[re, -im], [im, re]] C^{c_b},
 * (re, im) the element entry of `kind` with the per-corner frame field cfield
 * (turned by the corners' rotations, glpgp_ctri_turn_entry). */
GLPGP_FN void glpgp_crow_asm_quad(int i, int kind, double h, int sized, GLPGP_GLOBAL const double *sz,
                                  GLPGP_GLOBAL const double *xy, GLPGP_GLOBAL const double *txy,
                                  GLPGP_GLOBAL const int *tri, GLPGP_GLOBAL const unsigned char *cconj,
                                  GLPGP_GLOBAL const double *crot, GLPGP_GLOBAL const double *cfield,
                                  GLPGP_GLOBAL const int *rowptr, GLPGP_GLOBAL const int *cptr,
                                  GLPGP_GLOBAL const int *contrib, GLPGP_GLOBAL double *quad)
{
    for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
        double b0 = 0.0, b1 = 0.0, b2 = 0.0, b3 = 0.0;
        for (int c = cptr[k]; c < cptr[k + 1]; c++) {
            const int e = contrib[c], t = e / 9, a = (e % 9) / 3, b = e % 3;
            double x[3], y[3], wx[3], wy[3], er, ei;
            glpgp_ctri_load(xy, txy, tri, t, x, y);
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
            glpgp_ctri_turn_entry(crot, t, a, b, &er, &ei);
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

/* The penalty Hessian blocks (a, 0..2) of virtual triangle t (hm as
 * glpgp_pen_hess_row stores them: m00, m01, m11 per b) pulled back through
 * the corners' rotations: out[4b .. 4b+3] = R(r_a)^T M_b R(r_b), row-major
 * (without the conjugation signs, applied by the caller). */
GLPGP_FN void glpgp_ctri_turn_hess(GLPGP_GLOBAL const double *crot, int t, int a, const double *hm, double *out)
{
    const double ca = crot[2 * (3 * t + a)], sa = crot[2 * (3 * t + a) + 1];
    for (int b = 0; b < 3; b++) {
        const double cb = crot[2 * (3 * t + b)], sb = crot[2 * (3 * t + b) + 1];
        const double m00 = hm[3 * b], m01 = hm[3 * b + 1], m11 = hm[3 * b + 2];
        /* Q = M R_b, P = R_a^T Q */
        const double q00 = m00 * cb + m01 * sb, q01 = m01 * cb - m00 * sb;
        const double q10 = m01 * cb + m11 * sb, q11 = m11 * cb - m01 * sb;
        out[4 * b] = ca * q00 + sa * q10;
        out[4 * b + 1] = ca * q01 + sa * q11;
        out[4 * b + 2] = ca * q10 - sa * q00;
        out[4 * b + 3] = ca * q11 - sa * q01;
    }
}
/* NEWTON block row i and DINV_i of the coupled system: glpgp_row_asm_newton
 * with the penalty Hessian blocks of each virtual triangle evaluated at its
 * frame values and pulled back, [[m00, s_b m01], [s_a m01, s_a s_b m11]].
 * Returns 1 when the diagonal block is singular (DINV_i = 0), else 0. */
GLPGP_FN int glpgp_crow_asm_newton(int i, int hess, double inv4e2, GLPGP_GLOBAL const double *xy,
                                   GLPGP_GLOBAL const double *txy, GLPGP_GLOBAL const int *tri,
                                   GLPGP_GLOBAL const unsigned char *cconj, GLPGP_GLOBAL const double *crot,
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
            double x[3], y[3], zr[3], zi[3], hm[9], hr[12];
            glpgp_ctri_load(xy, txy, tri, t, x, y);
            glpgp_ctri_vals(tri, cconj, crot, z, t, zr, zi);
            glpgp_pen_hess_row(hess, glpgp_tri_area(x, y), inv4e2, zr, zi, a, hm);
            if (crot) glpgp_ctri_turn_hess(crot, t, a, hm, hr);
            const double sa = cconj[3 * t + a] ? -1.0 : 1.0;
            for (int b = 0; b < 3; b++) {
                const int j = tri[3 * t + b];
                if (dir[j]) continue;
                int k = k0;
                while (k < k1 && col[k] != j) k++;
                if (k == k1) continue;
                const double sb = cconj[3 * t + b] ? -1.0 : 1.0;
                GLPGP_GLOBAL double *blk = newton + 4 * (long)k;
                if (crot) {
                    blk[0] += hr[4 * b];
                    blk[1] += sb * hr[4 * b + 1];
                    blk[2] += sa * hr[4 * b + 2];
                    blk[3] += (sa * sb) * hr[4 * b + 3];
                    continue;
                }
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
 * corners (t, a) of node i of C^{c_a} R(r_a)^T dP_t/dz_a (frame values); 0 when dir[i];
 * *e += x_i . (QUAD x)_i. */
GLPGP_FN void glpgp_crow_gradient(int i, double inv4e2, GLPGP_GLOBAL const double *xy,
                                  GLPGP_GLOBAL const double *txy, GLPGP_GLOBAL const int *tri,
                                  GLPGP_GLOBAL const unsigned char *cconj, GLPGP_GLOBAL const double *crot,
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
            glpgp_ctri_load(xy, txy, tri, t, tx, ty);
            glpgp_ctri_vals(tri, cconj, crot, x, t, zr, zi);
            glpgp_pen_grad(glpgp_tri_area(tx, ty), inv4e2, zr, zi, a, &er, &ei);
            if (crot) { /* R(r_a)^T */
                const double c = crot[2 * (3 * t + a)], s = crot[2 * (3 * t + a) + 1];
                const double gr = c * er + s * ei, gi = c * ei - s * er;
                er = gr;
                ei = gi;
            }
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
