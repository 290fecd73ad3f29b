/* backend_linalg.cl: vector and sparse kernels of the OpenCL backend:
 * axpby, dot partials, 2x2-block CSR spmv, and the fused Jacobi-PCG steps
 * that read alpha and beta from the device scalar registers s[] (no host
 * round trip inside a CG iteration). Each kernel loops over its index range
 * [lo, hi) calling the per-entry / per-row body of kernels/rows.h that the C
 * reference also calls; only the order of the final dot-product sums differs
 * (per-work-item partials + glpgp_finalize, see backend_common.cl). */

/* y <- a x + c y, entries [lo, hi) (glpgp_entry_axpby: a zero coefficient does not
 * read its vector). */
GLPGP_KERNEL void glpgp_axpby(int n, int chunk, double a, __global const double *x, double c,
                              __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_entry_axpby(i, a, x, c, y);
}

/* part[off + group] <- sum over entries [lo, hi) of x_i y_i. */
GLPGP_KERNEL void glpgp_dot_part(int n, int chunk, __global const double *x,
                                 __global const double *y, __global double *part, int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    glpgp_group_sum(glpgp_range_dot(lo, hi, x, y), buf, part + off);
}

/* y_i <- sum_k A_ik x_col(k), block rows [lo, hi). */
GLPGP_KERNEL void glpgp_spmv(int n, int chunk, __global const int *rowptr,
                             __global const int *col, __global const double *A,
                             __global const double *x, __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_row_spmv_store(i, rowptr, col, A, x, y);
}

/* CG start, vertices [lo, hi):  z_i <- DINV_i r_i;
 * part[g] <- partial r.z,  part[off1 + g] <- partial r.r. */
GLPGP_KERNEL void glpgp_cg_precond(int n, int chunk, __global const double *dinv,
                                   __global const double *r, __global double *z,
                                   __global double *part, int off1)
{
    __local double buf[2 * GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double s1 = 0.0, s2 = 0.0;
    for (int i = lo; i < hi; i++) glpgp_row_precond(i, dinv, r, z, &s1, &s2);
    glpgp_group_sum2(s1, s2, buf, part, part + off1);
}

/* q <- A p (block rows [lo, hi));  part[off + group] <- partial p.q. */
GLPGP_KERNEL void glpgp_cg_spmv_dot(int n, int chunk, __global const int *rowptr,
                                    __global const int *col, __global const double *A,
                                    __global const double *p, __global double *q,
                                    __global double *part, int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double s = 0.0;
    for (int i = lo; i < hi; i++) glpgp_row_spmv_dot(i, rowptr, col, A, p, q, &s);
    glpgp_group_sum(s, buf, part + off);
}

/* CG update, vertices [lo, hi):  alpha = s[rz] / s[PQ];
 *   x <- x + alpha p;  r <- r - alpha q;  z <- DINV r;
 *   part[g] <- partial r.z,  part[off1 + g] <- partial r.r. */
GLPGP_KERNEL void glpgp_cg_update(int n, int chunk, __global const double *s, int rz,
                                  __global double *x, __global double *r,
                                  __global const double *p, __global const double *q,
                                  __global const double *dinv, __global double *z,
                                  __global double *part, int off1)
{
    __local double buf[2 * GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    const double alpha = glpgp_cg_alpha(s, rz);
    double s1 = 0.0, s2 = 0.0;
    for (int i = lo; i < hi; i++) glpgp_row_cg_update(i, alpha, x, r, p, q, dinv, z, &s1, &s2);
    glpgp_group_sum2(s1, s2, buf, part, part + off1);
}

/* CG direction, entries [lo, hi):  beta = s[rz_new] / s[rz];  p <- z + beta p. */
GLPGP_KERNEL void glpgp_cg_direction(int n, int chunk, __global const double *s, int rz_new,
                                     int rz, __global double *p, __global const double *z)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    const double beta = glpgp_cg_beta(s, rz_new, rz);
    for (int i = lo; i < hi; i++) glpgp_entry_cg_direction(i, beta, p, z);
}
