/* backend_coupled.cl: the mesh kernels of the coupled cross-field system
 * (solver/coupled.c, issue 14 item 3): QUAD, NEWTON (+ DINV), the gradient
 * and the penalty energy with each virtual corner's conjugation flag
 * (cconj) and frame field (cfield), and on a surface each triangle's own
 * plane (txy) and each corner's rotation (crot; both NULL otherwise). Each kernel loops over its index range
 * calling the per-row body of kernels/coupled_rows.h that the C reference
 * calls too, so both backends store bit-identical rows; the generic
 * kernels (spmv, CG, multigrid) serve the coupled system unchanged. */

/* QUAD of the coupled system, rows [lo, hi) (glpgp_crow_asm_quad). */
GLPGP_KERNEL void glpgp_casm_quad(int n, int chunk, int kind, double h, __global const double *xy,
                                  __global const double *txy, __global const int *tri,
                                  __global const uchar *cconj, __global const double *crot,
                                  __global const double *cfield, __global const int *rowptr,
                                  __global const int *cptr, __global const int *contrib,
                                  __global double *quad, int sized, __global const double *sz)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++)
        glpgp_crow_asm_quad(i, kind, h, sized, sz, xy, txy, tri, cconj, crot, cfield, rowptr, cptr, contrib, quad);
}

/* NEWTON and DINV of the coupled system, rows [lo, hi) (glpgp_crow_asm_newton);
 * a singular diagonal block records the smallest such node in *bad. */
GLPGP_KERNEL void glpgp_casm_newton(int n, int chunk, int hess, double inv4e2,
                                    __global const double *xy, __global const double *txy,
                                    __global const int *tri, __global const uchar *cconj,
                                    __global const double *crot, __global const double *z,
                                    __global const int *rowptr, __global const int *col,
                                    __global const int *diag, __global const int *vptr,
                                    __global const int *vtri, __global const uchar *dir,
                                    __global const double *quad, __global double *newton,
                                    __global double *dinv, __global int *bad)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++)
        if (glpgp_crow_asm_newton(i, hess, inv4e2, xy, txy, tri, cconj, crot, z, rowptr, col, diag, vptr, vtri, dir,
                                  quad, newton, dinv))
            atomic_min(bad, i);
}

/* Gradient of the coupled system, rows [lo, hi) (glpgp_crow_gradient);
 * part[off + group] <- partial sum of x . (QUAD x). */
GLPGP_KERNEL void glpgp_cgradient(int n, int chunk, double inv4e2, __global const double *xy,
                                  __global const double *txy, __global const int *tri,
                                  __global const uchar *cconj, __global const double *crot,
                                  __global const double *x, __global const int *rowptr,
                                  __global const int *col, __global const double *quad,
                                  __global const int *vptr, __global const int *vtri,
                                  __global const uchar *dir, __global double *g, __global double *part,
                                  int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double e = 0.0;
    for (int i = lo; i < hi; i++)
        glpgp_crow_gradient(i, inv4e2, xy, txy, tri, cconj, crot, x, rowptr, col, quad, vptr, vtri, dir, g, &e);
    glpgp_group_sum(e, buf, part + off);
}

/* Penalty energy at the frame values, virtual triangles [lo, hi)
 * (glpgp_ctri_pen_energy): part[off + group] <- sum_t P_t(x). */
GLPGP_KERNEL void glpgp_cpen_energy_part(int n, int chunk, double inv4e2, __global const double *xy,
                                         __global const double *txy, __global const int *tri,
                                         __global const uchar *cconj, __global const double *crot,
                                         __global const double *x, __global double *part, int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double p = 0.0;
    for (int t = lo; t < hi; t++) p += glpgp_ctri_pen_energy(t, inv4e2, xy, txy, tri, cconj, crot, x);
    glpgp_group_sum(p, buf, part + off);
}
