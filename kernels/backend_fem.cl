/* backend_fem.cl: mesh kernels of the OpenCL backend: atomic-free gather
 * assembly of QUAD and NEWTON (+ DINV), the GL gradient, and the per-triangle
 * penalty energy. Each kernel loops over its index range [lo, hi) calling the
 * per-row body of kernels/rows.h that the C reference also calls, so the
 * summation order per row equals the reference's:
 *   - block slot k sums contrib[cptr[k] .. cptr[k+1]) in slot-map order;
 *   - vertex i sums its penalty-gradient terms over vtri[vptr[i] .. vptr[i+1]).
 * Index ranges and reductions: see backend_common.cl. Matrices are 2x2-block
 * CSR (4 doubles a block, row-major); vectors hold [Re, Im] per vertex. */

/* QUAD <- sum over triangles of the element matrices (gather form), rows [lo, hi)
 * (glpgp_row_asm_quad). */
GLPGP_KERNEL void glpgp_asm_quad(int n, int chunk, int kind, double h, __global const double *xy,
                                 __global const int *tri, __global const double *w,
                                 __global const int *rowptr, __global const int *cptr,
                                 __global const int *contrib, __global double *quad, int sized,
                                 __global const double *sz)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++)
        glpgp_row_asm_quad(i, kind, h, sized, sz, xy, tri, w, rowptr, cptr, contrib, quad);
}

/* NEWTON <- QUAD + penalty Hessian (variant hess, weight inv4e2, at z), Dirichlet rows and
 * columns -> identity; DINV_i <- inverse of NEWTON's diagonal block i; rows [lo, hi)
 * (glpgp_row_asm_newton). A singular diagonal block records the smallest such vertex
 * in *bad. */
GLPGP_KERNEL void glpgp_asm_newton(int n, int chunk, int hess, double inv4e2,
                                   __global const double *xy, __global const int *tri,
                                   __global const double *z, __global const int *rowptr,
                                   __global const int *col, __global const int *diag,
                                   __global const int *vptr, __global const int *vtri,
                                   __global const uchar *dir, __global const double *quad,
                                   __global double *newton, __global double *dinv,
                                   __global int *bad)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++)
        if (glpgp_row_asm_newton(i, hess, inv4e2, xy, tri, z, rowptr, col, diag, vptr, vtri, dir,
                                 quad, newton, dinv))
            atomic_min(bad, i);
}

/* Gradient, rows [lo, hi):  g_i <- (QUAD x)_i + grad_i P(x)  (zero when i is Dirichlet;
 * glpgp_row_gradient);  part[off + group] <- partial sum of x . (QUAD x)  (E = 1/2 of it). */
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
    for (int i = lo; i < hi; i++)
        glpgp_row_gradient(i, inv4e2, xy, tri, x, rowptr, col, quad, vptr, vtri, dir, g, &e);
    glpgp_group_sum(e, buf, part + off);
}

/* Penalty energy, triangles [lo, hi):  part[off + group] <- sum_t P_t(x)
 * (glpgp_tri_pen_energy). */
GLPGP_KERNEL void glpgp_pen_energy_part(int n, int chunk, double inv4e2,
                                        __global const double *xy, __global const int *tri,
                                        __global const double *x, __global double *part,
                                        int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double p = 0.0;
    for (int t = lo; t < hi; t++) p += glpgp_tri_pen_energy(t, inv4e2, xy, tri, x);
    glpgp_group_sum(p, buf, part + off);
}
