/* backend_linalg.cl: vector and sparse kernels of the OpenCL backend:
 * axpby, dot partials, 2x2-block CSR spmv, and the fused Jacobi-PCG steps
 * that read alpha and beta from the device scalar registers s[] (no host
 * round trip inside a CG iteration). Arithmetic per entry matches
 * backend_ref.c; only the order of the final dot-product sums differs
 * (per-work-item partials + glpgp_finalize, see backend_common.cl). */

/* Slot of p.Ap in s[] (backend.h: GLPGP_S_PQ). */
#define GLPGP_CL_S_PQ 2

/* y <- a x + c y, entries [lo, hi). */
GLPGP_KERNEL void glpgp_axpby(int n, int chunk, double a, __global const double *x, double c,
                              __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) y[i] = a * x[i] + c * y[i];
}

/* part[off + group] <- sum over entries [lo, hi) of x_i y_i. */
GLPGP_KERNEL void glpgp_dot_part(int n, int chunk, __global const double *x,
                                 __global const double *y, __global double *part, int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double s = 0.0;
    for (int i = lo; i < hi; i++) s += x[i] * y[i];
    glpgp_group_sum(s, buf, part + off);
}

/* y_i <- sum_k A_ik x_col(k), block rows [lo, hi). */
GLPGP_KERNEL void glpgp_spmv(int n, int chunk, __global const int *rowptr,
                             __global const int *col, __global const double *A,
                             __global const double *x, __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) {
        double y0, y1;
        glpgp_block_row(i, rowptr, col, A, x, &y0, &y1);
        y[2 * i] = y0;
        y[2 * i + 1] = y1;
    }
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
    for (int i = lo; i < hi; i++) {
        __global const double *d = dinv + 4 * (long)i;
        const double r0 = r[2 * i], r1 = r[2 * i + 1];
        const double z0 = d[0] * r0 + d[1] * r1, z1 = d[2] * r0 + d[3] * r1;
        z[2 * i] = z0;
        z[2 * i + 1] = z1;
        s1 += r0 * z0 + r1 * z1;
        s2 += r0 * r0 + r1 * r1;
    }
    glpgp_group_sum2(s1, s2, buf, part, part + off1);
}

/* q <- NEWTON p (block rows [lo, hi));  part[off + group] <- partial p.q. */
GLPGP_KERNEL void glpgp_cg_spmv_dot(int n, int chunk, __global const int *rowptr,
                                    __global const int *col, __global const double *A,
                                    __global const double *p, __global double *q,
                                    __global double *part, int off)
{
    __local double buf[GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double s = 0.0;
    for (int i = lo; i < hi; i++) {
        double y0, y1;
        glpgp_block_row(i, rowptr, col, A, p, &y0, &y1);
        q[2 * i] = y0;
        q[2 * i + 1] = y1;
        s += p[2 * i] * y0;
        s += p[2 * i + 1] * y1;
    }
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
    const double alpha = s[rz] / s[GLPGP_CL_S_PQ];
    double s1 = 0.0, s2 = 0.0;
    for (int i = lo; i < hi; i++) {
        x[2 * i] += alpha * p[2 * i];
        x[2 * i + 1] += alpha * p[2 * i + 1];
        const double r0 = r[2 * i] - alpha * q[2 * i];
        const double r1 = r[2 * i + 1] - alpha * q[2 * i + 1];
        r[2 * i] = r0;
        r[2 * i + 1] = r1;
        __global const double *d = dinv + 4 * (long)i;
        const double z0 = d[0] * r0 + d[1] * r1, z1 = d[2] * r0 + d[3] * r1;
        z[2 * i] = z0;
        z[2 * i + 1] = z1;
        s1 += r0 * z0 + r1 * z1;
        s2 += r0 * r0 + r1 * r1;
    }
    glpgp_group_sum2(s1, s2, buf, part, part + off1);
}

/* CG direction, entries [lo, hi):  beta = s[rz_new] / s[rz];  p <- z + beta p. */
GLPGP_KERNEL void glpgp_cg_direction(int n, int chunk, __global const double *s, int rz_new,
                                     int rz, __global double *p, __global const double *z)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    const double beta = s[rz_new] / s[rz];
    for (int i = lo; i < hi; i++) p[i] = z[i] + beta * p[i];
}
