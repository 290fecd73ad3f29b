/* backend_fem.cl: mesh kernels of the OpenCL backend: atomic-free gather
 * assembly of QUAD and NEWTON (+ DINV), the GL gradient, and the per-triangle
 * penalty energy. Every per-triangle quantity comes from kernels/element.h
 * (glpgp_elem_entry, glpgp_pen_hess, glpgp_pen_grad, glpgp_pen_energy,
 * glpgp_tri_area); the summation order equals backend_ref.c's:
 *   - block slot k sums contrib[cptr[k] .. cptr[k+1]) in slot-map order;
 *   - vertex i sums its penalty-gradient terms over vtri[vptr[i] .. vptr[i+1]).
 * Index ranges and reductions: see backend_common.cl. Matrices are 2x2-block
 * CSR (4 doubles a block, row-major); vectors hold [Re, Im] per vertex. */

/* Corner coordinates of triangle t into private arrays x, y. */
void glpgp_cl_tri_load(__global const double *xy, __global const int *tri, int t, double *x,
                       double *y)
{
    for (int a = 0; a < 3; a++) {
        const int v = tri[3 * t + a];
        x[a] = xy[2 * v];
        y[a] = xy[2 * v + 1];
    }
}

/* Corner values (Re, Im) of the 2-per-vertex vector v on triangle t. */
void glpgp_cl_tri_vals(__global const int *tri, __global const double *v, int t, double *vr,
                       double *vi)
{
    for (int a = 0; a < 3; a++) {
        const int i = tri[3 * t + a];
        vr[a] = v[2 * i];
        vi[a] = v[2 * i + 1];
    }
}

/* QUAD <- sum over triangles of the element matrices (gather form), rows [lo, hi):
 *   block(k) = sum_{(t,a,b) in contrib(k)} H_T(a,b),  H = re + i im  ->  [[re, -im], [im, re]] */
GLPGP_KERNEL void glpgp_asm_quad(int n, int chunk, int kind, double h, __global const double *xy,
                                 __global const int *tri, __global const double *w,
                                 __global const int *rowptr, __global const int *cptr,
                                 __global const int *contrib, __global double *quad)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) {
        for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
            double re = 0.0, im = 0.0;
            for (int c = cptr[k]; c < cptr[k + 1]; c++) {
                const int e = contrib[c], t = e / 9, a = (e % 9) / 3, b = e % 3;
                double x[3], y[3], wx[3], wy[3], er, ei;
                glpgp_cl_tri_load(xy, tri, t, x, y);
                glpgp_cl_tri_vals(tri, w, t, wx, wy);
                glpgp_elem_entry(kind, x, y, wx, wy, h, a, b, &er, &ei);
                re += er;
                im += ei;
            }
            __global double *blk = quad + 4 * (long)k;
            blk[0] = re;
            blk[1] = -im;
            blk[2] = im;
            blk[3] = re;
        }
    }
}

/* NEWTON <- QUAD + penalty Hessian (variant hess, weight inv4e2, at z), rows [lo, hi);
 * a block in a Dirichlet row or column becomes identity (diagonal) or zero;
 * DINV_i <- inverse of NEWTON's diagonal block i:
 *   [[d0, d1], [d2, d3]]^-1 = [[d3, -d1], [-d2, d0]] / (d0 d3 - d1 d2).
 * A singular diagonal block records the smallest such vertex in *bad. */
GLPGP_KERNEL void glpgp_asm_newton(int n, int chunk, int hess, double inv4e2,
                                   __global const double *xy, __global const int *tri,
                                   __global const double *z, __global const int *rowptr,
                                   __global const int *col, __global const int *diag,
                                   __global const int *cptr, __global const int *contrib,
                                   __global const uchar *dir, __global const double *quad,
                                   __global double *newton, __global double *dinv,
                                   __global int *bad)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) {
        for (int k = rowptr[i]; k < rowptr[i + 1]; k++) {
            const int j = col[k];
            __global double *blk = newton + 4 * (long)k;
            if (dir[i] || dir[j]) {
                const double d = (i == j) ? 1.0 : 0.0;
                blk[0] = d;
                blk[1] = 0.0;
                blk[2] = 0.0;
                blk[3] = d;
                continue;
            }
            double m0 = 0.0, m1 = 0.0, m2 = 0.0, m3 = 0.0;
            if (inv4e2 > 0.0) {
                for (int c = cptr[k]; c < cptr[k + 1]; c++) {
                    const int e = contrib[c], t = e / 9, a = (e % 9) / 3, b = e % 3;
                    double x[3], y[3], zr[3], zi[3], hm[4];
                    glpgp_cl_tri_load(xy, tri, t, x, y);
                    glpgp_cl_tri_vals(tri, z, t, zr, zi);
                    glpgp_pen_hess(hess, glpgp_tri_area(x, y), inv4e2, zr, zi, a, b, hm);
                    m0 += hm[0];
                    m1 += hm[1];
                    m2 += hm[2];
                    m3 += hm[3];
                }
            }
            __global const double *qb = quad + 4 * (long)k;
            blk[0] = qb[0] + m0;
            blk[1] = qb[1] + m1;
            blk[2] = qb[2] + m2;
            blk[3] = qb[3] + m3;
        }
        __global const double *d = newton + 4 * (long)diag[i];
        const double det = d[0] * d[3] - d[1] * d[2];
        __global double *o = dinv + 4 * (long)i;
        if (det == 0.0) {
            atomic_min(bad, i);
            o[0] = o[1] = o[2] = o[3] = 0.0;
            continue;
        }
        o[0] = d[3] / det;
        o[1] = -d[1] / det;
        o[2] = -d[2] / det;
        o[3] = d[0] / det;
    }
}

/* Gradient, rows [lo, hi):  g_i <- (QUAD x)_i + sum_{(t,a) in vtri(i)} dP_t/dX_a  (zero
 * when i is Dirichlet);  part[off + group] <- partial sum of x . (QUAD x)  (E = 1/2 of it). */
GLPGP_KERNEL void glpgp_gradient(int n, int chunk, double inv4e2, __global const double *xy,
                                 __global const int *tri, __global const double *x,
                                 __global const int *rowptr, __global const int *col,
                                 __global const double *quad, __global const int *vptr,
                                 __global const int *vtri, __global const uchar *dir,
                                 __global double *g, __global double *part, int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double e = 0.0;
    for (int i = lo; i < hi; i++) {
        double y0, y1;
        glpgp_block_row(i, rowptr, col, quad, x, &y0, &y1);
        e += x[2 * i] * y0;
        e += x[2 * i + 1] * y1;
        if (dir[i]) {
            y0 = 0.0;
            y1 = 0.0;
        } else if (inv4e2 > 0.0) {
            double gr = 0.0, gi = 0.0;
            for (int p = vptr[i]; p < vptr[i + 1]; p++) {
                const int t = vtri[p] / 3, a = vtri[p] % 3;
                double tx[3], ty[3], zr[3], zi[3], er, ei;
                glpgp_cl_tri_load(xy, tri, t, tx, ty);
                glpgp_cl_tri_vals(tri, x, t, zr, zi);
                glpgp_pen_grad(glpgp_tri_area(tx, ty), inv4e2, zr, zi, a, &er, &ei);
                gr += er;
                gi += ei;
            }
            y0 += gr;
            y1 += gi;
        }
        g[2 * i] = y0;
        g[2 * i + 1] = y1;
    }
    glpgp_group_sum(e, buf, part + off);
}

/* Penalty energy, triangles [lo, hi):  part[off + group] <- sum_t P_t(x). */
GLPGP_KERNEL void glpgp_pen_energy_part(int n, int chunk, double inv4e2,
                                        __global const double *xy, __global const int *tri,
                                        __global const double *x, __global double *part,
                                        int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double p = 0.0;
    for (int t = lo; t < hi; t++) {
        double tx[3], ty[3], zr[3], zi[3];
        glpgp_cl_tri_load(xy, tri, t, tx, ty);
        glpgp_cl_tri_vals(tri, x, t, zr, zi);
        p += glpgp_pen_energy(glpgp_tri_area(tx, ty), inv4e2, zr, zi);
    }
    glpgp_group_sum(p, buf, part + off);
}
