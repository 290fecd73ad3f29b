/* backend_newton.cl: the Newton driver's per-vertex work beside the matrices
 * (ops of glpgp/backend.h that solver/newton.c calls between assemblies):
 * the trust region's trial point. Each kernel loops over its index range
 * calling the per-vertex body of kernels/newton_rows.h, which the reference
 * backend calls too (bit-identical). */

/* Vertices [lo, hi):  xt_i <- x_i (+) a d_i  (glpgp_row_trial_point). */
GLPGP_KERNEL void glpgp_trial_point(int n, int chunk, __global const double *x, __global const double *d, double a,
                                    double r1, __global double *xt)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_row_trial_point(i, x, d, a, r1, xt);
}
