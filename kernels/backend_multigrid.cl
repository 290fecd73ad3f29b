/* backend_multigrid.cl: the kernels of the aggregation multigrid
 * preconditioner's ops (amg_* of glpgp/backend.h) in the OpenCL backend
 * (host/backends/opencl.c). Each kernel loops over its index range [lo, hi)
 * (rows, aggregates, coarse rows or vector entries; GLPGP_RANGE of
 * backend_common.cl, both launch shapes) calling the per-row body of
 * kernels/amg_rows.h that the C reference (host/backends/reference_amg.c)
 * calls, so every stored value is bit-identical to the reference; only dot
 * products differ, in the order of the final sum (per-work-group partials,
 * then glpgp_amg_finalize; a launch of a single work-group writes its sum
 * straight into the register, which the host uses on small levels to save
 * the finalize launch).
 *
 * The AMG scalar registers t[] (GLPGP_AMG_NSLOTS doubles) are a device
 * buffer of their own; coefficients are read from them inside the kernels
 * (no host round trip inside a cycle). Arguments 0 and 1 of every kernel
 * are (n, chunk), set by the host's launch helper. Vectors that a flag says
 * are absent (has_x = 0, ...) are not read; the host passes any valid buffer. */

/* Three sums at once: v[q] -> out[q * stride + group] for the q with bit q of
 * mask set (buf: 3 * GLPGP_WG doubles of local memory). */
void glpgp_amg_group_sum3(double v0, double v1, double v2, int mask, __local double *buf,
                          __global double *out, int stride)
{
    const int g = (int)get_group_id(0);
#if GLPGP_WG == 1
    (void)buf;
#else
    const int l = (int)get_local_id(0);
    buf[l] = v0;
    buf[GLPGP_WG + l] = v1;
    buf[2 * GLPGP_WG + l] = v2;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int s = GLPGP_WG / 2; s > 0; s >>= 1) {
        if (l < s) {
            buf[l] += buf[l + s];
            buf[GLPGP_WG + l] += buf[GLPGP_WG + l + s];
            buf[2 * GLPGP_WG + l] += buf[2 * GLPGP_WG + l + s];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (l != 0) return;
    v0 = buf[0];
    v1 = buf[GLPGP_WG];
    v2 = buf[2 * GLPGP_WG];
#endif
    if (mask & 1) out[g] = v0;
    if (mask & 2) out[stride + g] = v1;
    if (mask & 4) out[2 * stride + g] = v2;
}

/* Second reduction stage, ONE work-group of GLPGP_WG items: for each q with
 * bit q of mask set,  t[slot + q] <- sum_{g < np} part[q * stride + g]
 * (work-item l sums l, l + WG, ...; then a tree). */
GLPGP_KERNEL void glpgp_amg_finalize(__global const double *part, int np, int stride, int mask,
                                     __global double *t, int slot)
{
    __local double buf[3 * GLPGP_WG];
    const int l = (int)get_local_id(0);
    double a[3] = {0.0, 0.0, 0.0};
    for (int q = 0; q < 3; q++)
        if (mask & (1 << q))
            for (int g = l; g < np; g += GLPGP_WG) a[q] += part[q * stride + g];
#if GLPGP_WG > 1
    for (int q = 0; q < 3; q++) buf[q * GLPGP_WG + l] = a[q];
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int h = GLPGP_WG / 2; h > 0; h >>= 1) {
        if (l < h)
            for (int q = 0; q < 3; q++) buf[q * GLPGP_WG + l] += buf[q * GLPGP_WG + l + h];
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    for (int q = 0; q < 3; q++) a[q] = buf[q * GLPGP_WG];
#else
    (void)buf;
#endif
    if (l == 0)
        for (int q = 0; q < 3; q++)
            if (mask & (1 << q)) t[slot + q] = a[q];
}

/* ---- hierarchy values (per Newton step) ------------------------------------ */

/* Aggregates [lo, hi) of level l: amp_next[J] <- s_J, c_i <- f_i / s_J
 * (glpgp_amg_agg_weights). */
GLPGP_KERNEL void glpgp_amg_weights(int n, int chunk, __global const int *aptr, __global const int *amem,
                                    int has_amp, __global const double *amp, int has_frame,
                                    __global const double *fr, int has_dir, __global const uchar *dir,
                                    __global double *c, __global double *amp_next)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int J = lo; J < hi; J++)
        glpgp_amg_agg_weights(J, aptr, amem, has_amp, amp, has_frame, fr, has_dir, dir, c, amp_next);
}

/* Coarse rows [lo, hi) of A_{l+1} = P^T A_l P (glpgp_amg_galerkin_row); with
 * do_l1, the row's l1 smoother block too (glpgp_amg_l1_row on the values just
 * written by this work-item). */
GLPGP_KERNEL void glpgp_amg_galerkin(int n, int chunk, __global const int *crowptr,
                                     __global const int *cdiag, __global const int *gptr,
                                     __global const int *gsrc, __global const int *srow,
                                     __global const int *col, __global const double *c,
                                     __global const double *A, __global const double *amp_c,
                                     __global double *Ac, int do_l1, double w, __global double *minv_c)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int I = lo; I < hi; I++) {
        glpgp_amg_galerkin_row(I, crowptr, cdiag, gptr, gsrc, srow, col, c, A, amp_c, Ac);
        if (do_l1) glpgp_amg_l1_row(I, crowptr, cdiag, Ac, w, minv_c);
    }
}

/* Rows [lo, hi): l1 smoother blocks of A (glpgp_amg_l1_row). */
GLPGP_KERNEL void glpgp_amg_l1(int n, int chunk, __global const int *rowptr, __global const int *diag,
                               __global const double *A, double w, __global double *minv)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_amg_l1_row(i, rowptr, diag, A, w, minv);
}

/* The coarse solve operator from the coarsest level (n nodes): dense
 * expansion and its LU (spd = 0) or SPD (spd = 1) generalised inverse into
 * inv, by ONE work-group (kernels/amg_dense.h; W, I: its work arrays);
 * t[slot] <- the status (0, or 1: not finite). */
GLPGP_KERNEL void glpgp_amg_coarse_invert(int n, int spd, __global const int *rowptr, __global const int *col,
                                          __global const double *val, __global double *inv, __global double *W,
                                          __global int *I, __global double *t, int slot)
{
    __local double bv[GLPGP_WG];
    __local long bi[GLPGP_WG];
    const int st = glpgp_dense_coarse_invert((int)get_local_id(0), GLPGP_WG, n, rowptr, col, val, spd, inv, W, I, bv,
                                             bi);
    if (get_local_id(0) == 0) t[slot] = (double)st;
}

/* ---- the cycle ----------------------------------------------------------- */

/* Rows [lo, hi):  y_i <- x_i + M_i^-1 (r_i - (A x)_i)  (has_x = 0: M_i^-1 r_i). */
GLPGP_KERNEL void glpgp_amg_smooth(int n, int chunk, int has_x, __global const int *rowptr,
                                   __global const int *col, __global const double *A,
                                   __global const double *minv, __global const double *r,
                                   __global const double *x, __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_amg_row_smooth(i, has_x, rowptr, col, A, minv, r, x, y);
}

/* Aggregates [lo, hi):  rc_J <- sum_{i in J} P_i^T (r_i - (A x)_i)  (has_x = 0:
 * P_i^T r_i); the residual is formed on the fly, row by row. */
GLPGP_KERNEL void glpgp_amg_restrict(int n, int chunk, __global const int *aptr, __global const int *amem,
                                     __global const double *c, int has_x, __global const int *rowptr,
                                     __global const int *col, __global const double *A,
                                     __global const double *r, __global const double *x,
                                     __global double *rc)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int J = lo; J < hi; J++) glpgp_amg_agg_restrict(J, aptr, amem, c, has_x, rowptr, col, A, r, x, rc);
}

/* Rows [lo, hi):  t_i <- r_i - (A x)_i  (first pass of the restriction: the
 * aggregates then gather t, 2 doubles per member, instead of each reading
 * its members' rows scattered over the level). */
GLPGP_KERNEL void glpgp_amg_residual(int n, int chunk, __global const int *rowptr, __global const int *col,
                                     __global const double *A, __global const double *r,
                                     __global const double *x, __global double *t)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_amg_row_residual(i, rowptr, col, A, r, x, t);
}

/* Aggregates [lo, hi): y_i <- M_i^-1 r_i for their members and rc_J <- P^T
 * (r - A y) (glpgp_amg_agg_presmooth_restrict: a visit's first half in one
 * pass; the CPU launch shape). */
GLPGP_KERNEL void glpgp_amg_presmooth_restrict(int n, int chunk, __global const int *aptr, __global const int *amem,
                                               __global const double *c, __global const int *rowptr,
                                               __global const int *col, __global const double *A,
                                               __global const double *minv, __global const double *r,
                                               __global double *y, __global double *rc)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int J = lo; J < hi; J++) glpgp_amg_agg_presmooth_restrict(J, aptr, amem, c, rowptr, col, A, minv, r, y, rc);
}

/* Rows [lo, hi): y_i <- M_i^-1 r_i and t_i <- r_i - (A y)_i
 * (glpgp_amg_row_presmooth_resid; the GPU launch shape, whose aggregates
 * then gather t with glpgp_amg_restrict). */
GLPGP_KERNEL void glpgp_amg_presmooth_resid(int n, int chunk, __global const int *rowptr, __global const int *col,
                                            __global const double *A, __global const double *minv,
                                            __global const double *r, __global double *y, __global double *t)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) {
        double t0, t1;
        glpgp_amg_row_presmooth_resid(i, rowptr, col, A, minv, r, y, &t0, &t1);
        t[2 * i] = t0;
        t[2 * i + 1] = t1;
    }
}

/* Rows [lo, hi): y_i <- x'_i + M_i^-1 (r_i - (A x')_i), x' = x + P ec
 * (glpgp_amg_row_prolong_smooth: a visit's second half in one pass). */
GLPGP_KERNEL void glpgp_amg_prolong_smooth(int n, int chunk, __global const int *agg, __global const double *c,
                                           __global const double *ec, __global const int *rowptr,
                                           __global const int *col, __global const double *A,
                                           __global const double *minv, __global const double *r,
                                           __global const double *x, __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_amg_row_prolong_smooth(i, agg, c, ec, rowptr, col, A, minv, r, x, y);
}

/* Rows [lo, hi):  x_i <- x_i + P_i ec_agg(i). */
GLPGP_KERNEL void glpgp_amg_prolong(int n, int chunk, __global const int *agg, __global const double *c,
                                    __global const double *ec, __global double *x)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_amg_row_prolong(i, agg, c, ec, x);
}

/* Rows [lo, hi) of the dense coarse solve  x <- C r  (order n). */
GLPGP_KERNEL void glpgp_amg_dense(int n, int chunk, __global const double *C, __global const double *r,
                                  __global double *x)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    for (int i = lo; i < hi; i++) glpgp_amg_row_dense(i, n, C, r, x);
}

/* Rows [lo, hi):  y <- A x;  partials of x.y, x.u (has_u), x.w (has_w) into
 * part[off + g], part[off + stride + g], part[off + 2 stride + g] (one
 * work-group: off = slot, stride 1, part = t writes the registers). */
GLPGP_KERNEL void glpgp_amg_spmv_dots(int n, int chunk, __global const int *rowptr, __global const int *col,
                                      __global const double *A, __global const double *x,
                                      __global double *y, int has_u, __global const double *u, int has_w,
                                      __global const double *w, __global double *part, int off, int stride)
{
    __local double buf[3 * GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (int i = lo; i < hi; i++) {
        glpgp_row_spmv_dot(i, rowptr, col, A, x, y, &s0);
        if (has_u) glpgp_row_dot_acc(i, x, u[2 * i], u[2 * i + 1], &s1);
        if (has_w) glpgp_row_dot_acc(i, x, w[2 * i], w[2 * i + 1], &s2);
    }
    glpgp_amg_group_sum3(s0, s1, s2, 1 | (has_u ? 2 : 0) | (has_w ? 4 : 0), buf, part + off, stride);
}

/* Entries [lo, hi): partials of x.u (has_u), x.w (has_w) into part[off + g],
 * part[off + stride + g]. */
GLPGP_KERNEL void glpgp_amg_dots(int n, int chunk, __global const double *x, int has_u,
                                 __global const double *u, int has_w, __global const double *w,
                                 __global double *part, int off, int stride)
{
    __local double buf[3 * GLPGP_WG];
    GLPGP_RANGE(lo, hi, n, chunk);
    const double s0 = has_u ? glpgp_range_dot(lo, hi, x, u) : 0.0;
    const double s1 = has_w ? glpgp_range_dot(lo, hi, x, w) : 0.0;
    glpgp_amg_group_sum3(s0, s1, 0.0, (has_u ? 1 : 0) | (has_w ? 2 : 0), buf, part + off, stride);
}

/* Entries [lo, hi):  y <- a x + c y,  a = an/ad/as and c = cn/cd/cs
 * coefficients from the registers t (glpgp_amg_coef_value). */
GLPGP_KERNEL void glpgp_amg_axpby(int n, int chunk, __global const double *t, int an, int ad, double as,
                                  __global const double *x, int cn, int cd, double cs, __global double *y)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    const double p = glpgp_amg_coef_value(t, an, ad, as), q = glpgp_amg_coef_value(t, cn, cd, cs);
    for (int i = lo; i < hi; i++) glpgp_amg_entry_axpby(i, p, x, q, y);
}

/* Entries [lo, hi):  e <- c0 v + c1 d,  (c0, c1) = glpgp_amg_kcoef of
 * t[slot .. slot + 4]. */
GLPGP_KERNEL void glpgp_amg_kcombine(int n, int chunk, __global const double *t, int slot,
                                     __global const double *v, __global const double *d, __global double *e)
{
    GLPGP_RANGE(lo, hi, n, chunk);
    double cf[2];
    glpgp_amg_kcoef(t[slot], t[slot + 1], t[slot + 2], t[slot + 3], t[slot + 4], cf);
    for (int i = lo; i < hi; i++) glpgp_amg_entry_kcombine(i, cf[0], cf[1], v, d, e);
}

/* ---- fused coarse correction (CPU launch shape) ---------------------------
 * glpgp_amg_bottom runs the whole coarse correction of level lb and of every
 * level below it in ONE work-item: the sequence of solver/amg.c's
 * coarse_correction / cycle (pre and post l1-Jacobi sweeps, restriction,
 * K-cycle with its registers in t, plain visits, dense coarse solve; with
 * sym = 1 the symmetric cycle's: W-visits instead of K-cycles, the host
 * passing max(pre, post) as both sweep counts), each
 * step the same amg_rows.h body the per-op kernels call, dot products as one
 * sequential sum (the order of a one-work-group per-op launch and of the C
 * reference). So its result is bit-identical to the per-op path on those
 * levels, without one launch per operation (PoCL: several microseconds each,
 * hundreds per cycle on the small levels of a K-cycle).
 * OpenCL C has no recursion: the calls coarse_correction(c) -> cycle(c) ->
 * coarse_correction(c+1) alternate, so the call stack is implied by (level,
 * kind) and each level keeps its own resume point (pc_cc, pc_cy) and the
 * vectors of its active cycle (cy_r, cy_out, cy_cur, cy_k). The levels' data
 * live in two packed arrays (ip ints, dp doubles) at the offsets of the table
 * tab (GLPGP_AMG_BT_* columns, one row per level from lb). */

#define GLPGP_BT(q, f) tab[(q) * GLPGP_AMG_BT_COUNT + (f)]

/* y <- x + M^-1 (r - A x) on table row q (x < 0: x = 0), offsets into dp */
void glpgp_amg_bt_smooth(int q, __global const int *tab, __global const int *ip, __global double *dp, int r,
                         int x, int y)
{
    const int n = GLPGP_BT(q, GLPGP_AMG_BT_N);
    __global const int *rowptr = ip + GLPGP_BT(q, GLPGP_AMG_BT_ROWPTR), *col = ip + GLPGP_BT(q, GLPGP_AMG_BT_COL);
    __global const double *A = dp + GLPGP_BT(q, GLPGP_AMG_BT_VAL), *minv = dp + GLPGP_BT(q, GLPGP_AMG_BT_MINV);
    for (int i = 0; i < n; i++)
        glpgp_amg_row_smooth(i, x >= 0, rowptr, col, A, minv, dp + r, dp + (x >= 0 ? x : r), dp + y);
}

/* rc <- P^T (r - A x) on table row q (x < 0: P^T r), in row order: rc <- 0,
 * then each row adds into its aggregate (the same sums as the per-op
 * gather, bit for bit: members in increasing order from 0; the gather with
 * x read its rows aggregate by aggregate, scattered over the level, and was
 * the costliest step of a CAD solve's fused levels) */
void glpgp_amg_bt_restrict(int q, __global const int *tab, __global const int *ip, __global double *dp, int r,
                           int x, int rc)
{
    const int n = GLPGP_BT(q, GLPGP_AMG_BT_N), nc = GLPGP_BT(q, GLPGP_AMG_BT_NC);
    __global const int *rowptr = ip + GLPGP_BT(q, GLPGP_AMG_BT_ROWPTR), *col = ip + GLPGP_BT(q, GLPGP_AMG_BT_COL);
    __global const int *agg = ip + GLPGP_BT(q, GLPGP_AMG_BT_AGG);
    __global const double *A = dp + GLPGP_BT(q, GLPGP_AMG_BT_VAL), *c = dp + GLPGP_BT(q, GLPGP_AMG_BT_C);
    for (int J = 0; J < 2 * nc; J++) dp[rc + J] = 0.0;
    for (int i = 0; i < n; i++)
        glpgp_amg_row_restrict_scatter(i, agg, c, x >= 0, rowptr, col, A, dp + r, dp + (x >= 0 ? x : r),
                                       dp + rc);
}

/* x <- x + P ec on table row q */
void glpgp_amg_bt_prolong(int q, __global const int *tab, __global const int *ip, __global double *dp, int ec,
                          int x)
{
    const int n = GLPGP_BT(q, GLPGP_AMG_BT_N);
    __global const int *agg = ip + GLPGP_BT(q, GLPGP_AMG_BT_AGG);
    __global const double *c = dp + GLPGP_BT(q, GLPGP_AMG_BT_C);
    for (int i = 0; i < n; i++) glpgp_amg_row_prolong(i, agg, c, dp + ec, dp + x);
}

/* y <- A x;  t[slot] <- x.y;  t[slot+1] <- x.u (u >= 0);  t[slot+2] <- x.w (w >= 0) */
void glpgp_amg_bt_spmv_dots(int q, __global const int *tab, __global const int *ip, __global double *dp,
                            __global double *t, int x, int y, int u, int w, int slot)
{
    const int n = GLPGP_BT(q, GLPGP_AMG_BT_N);
    __global const int *rowptr = ip + GLPGP_BT(q, GLPGP_AMG_BT_ROWPTR), *col = ip + GLPGP_BT(q, GLPGP_AMG_BT_COL);
    __global const double *A = dp + GLPGP_BT(q, GLPGP_AMG_BT_VAL);
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) {
        glpgp_row_spmv_dot(i, rowptr, col, A, dp + x, dp + y, &s0);
        if (u >= 0) glpgp_row_dot_acc(i, dp + x, dp[u + 2 * i], dp[u + 2 * i + 1], &s1);
        if (w >= 0) glpgp_row_dot_acc(i, dp + x, dp[w + 2 * i], dp[w + 2 * i + 1], &s2);
    }
    t[slot] = s0;
    if (u >= 0) t[slot + 1] = s1;
    if (w >= 0) t[slot + 2] = s2;
}

/* y <- a x + c y over len entries (coefficients as glpgp_amg_coef) */
void glpgp_amg_bt_axpby(__global double *dp, __global const double *t, int len, int an, int ad, double as, int x,
                        int cn, int cd, double cs, int y)
{
    const double p = glpgp_amg_coef_value(t, an, ad, as), qq = glpgp_amg_coef_value(t, cn, cd, cs);
    for (int i = 0; i < len; i++) glpgp_amg_entry_axpby(i, p, dp + x, qq, dp + y);
}

GLPGP_KERNEL void glpgp_amg_bottom(int lb, int L, int pre, int post, int m, int cinv, __global const int *tab,
                                   __global const int *ip, __global double *dp, __global double *t,
                                   __global const double *rhs, __global double *out, int sym)
{
    if (get_global_id(0) != 0) return;
    enum { CC = 0, CY = 1 };
    int pc_cc[GLPGP_AMG_ROWS_MAX_LEVELS], pc_cy[GLPGP_AMG_ROWS_MAX_LEVELS];
    int cy_r[GLPGP_AMG_ROWS_MAX_LEVELS], cy_out[GLPGP_AMG_ROWS_MAX_LEVELS];
    int cy_cur[GLPGP_AMG_ROWS_MAX_LEVELS], cy_k[GLPGP_AMG_ROWS_MAX_LEVELS];
    /* b_lb <- rhs */
    {
        const int n2 = 2 * GLPGP_BT(0, GLPGP_AMG_BT_N), b = GLPGP_BT(0, GLPGP_AMG_BT_B);
        for (int i = 0; i < n2; i++) dp[b + i] = rhs[i];
    }
    int lev = lb, kind = CC;
    pc_cc[lb] = 0;
    /* coarse_correction(lev) calls cycle(lev) on r into out, resuming at pc */
#define GLPGP_BT_CALL_CYCLE(pc, r, out)                                                            \
    do {                                                                                           \
        pc_cc[lev] = (pc);                                                                         \
        cy_r[lev] = (r);                                                                           \
        cy_out[lev] = (out);                                                                       \
        pc_cy[lev] = 0;                                                                            \
        kind = CY;                                                                                 \
    } while (0)
    for (;;) {
        const int q = lev - lb;
        if (kind == CC) {
            /* coarse_correction(lev): e_lev <- B_lev b_lev */
            const int b = GLPGP_BT(q, GLPGP_AMG_BT_B), e = GLPGP_BT(q, GLPGP_AMG_BT_E);
            int ret = 0;
            if (lev == L - 1) {
                /* e <- C b (dense) */
                for (int i = 0; i < m; i++) glpgp_amg_row_dense(i, m, dp + cinv, dp + b, dp + e);
                ret = 1;
            } else if (!GLPGP_BT(q, GLPGP_AMG_BT_K)) {
                /* one plain visit: e <- cycle(b) */
                if (pc_cc[lev] == 0) {
                    GLPGP_BT_CALL_CYCLE(1, b, e);
                    continue;
                }
                ret = 1;
            } else if (sym) {
                /* the symmetric cycle's W-visit (solver/amg.c):
                 * e = B b; w = A e; r2 = b - w; d = B r2; e <- e + d */
                const int S = GLPGP_AMG_ROWS_KSLOT(lev), n2 = 2 * GLPGP_BT(q, GLPGP_AMG_BT_N);
                const int w = GLPGP_BT(q, GLPGP_AMG_BT_W), r2 = GLPGP_BT(q, GLPGP_AMG_BT_R2);
                const int d = GLPGP_BT(q, GLPGP_AMG_BT_D);
                if (pc_cc[lev] == 0) {
                    GLPGP_BT_CALL_CYCLE(1, b, e);
                    continue;
                }
                if (pc_cc[lev] == 1) {
                    glpgp_amg_bt_spmv_dots(q, tab, ip, dp, t, e, w, -1, -1, S);
                    glpgp_amg_bt_axpby(dp, t, n2, -1, -1, 1.0, b, -1, -1, 0.0, r2);
                    glpgp_amg_bt_axpby(dp, t, n2, -1, -1, -1.0, w, -1, -1, 1.0, r2);
                    GLPGP_BT_CALL_CYCLE(2, r2, d);
                    continue;
                }
                glpgp_amg_bt_axpby(dp, t, n2, -1, -1, 1.0, d, -1, -1, 1.0, e);
                ret = 1;
            } else {
                /* K-cycle: v = B b; w = A v; r2 = b - (v.b / v.w) w; d = B r2;
                 * wd = A d; e = kcombine(v, d) */
                const int S = GLPGP_AMG_ROWS_KSLOT(lev), n2 = 2 * GLPGP_BT(q, GLPGP_AMG_BT_N);
                const int v = GLPGP_BT(q, GLPGP_AMG_BT_V), w = GLPGP_BT(q, GLPGP_AMG_BT_W);
                const int r2 = GLPGP_BT(q, GLPGP_AMG_BT_R2), d = GLPGP_BT(q, GLPGP_AMG_BT_D);
                const int wd = GLPGP_BT(q, GLPGP_AMG_BT_WD);
                if (pc_cc[lev] == 0) {
                    GLPGP_BT_CALL_CYCLE(1, b, v);
                    continue;
                }
                if (pc_cc[lev] == 1) {
                    glpgp_amg_bt_spmv_dots(q, tab, ip, dp, t, v, w, b, -1, S);
                    glpgp_amg_bt_axpby(dp, t, n2, -1, -1, 1.0, b, -1, -1, 0.0, r2);
                    glpgp_amg_bt_axpby(dp, t, n2, S + 1, S, -1.0, w, -1, -1, 1.0, r2);
                    GLPGP_BT_CALL_CYCLE(2, r2, d);
                    continue;
                }
                glpgp_amg_bt_spmv_dots(q, tab, ip, dp, t, d, wd, w, r2, S + 2);
                {
                    double cf[2];
                    glpgp_amg_kcoef(t[S], t[S + 1], t[S + 2], t[S + 3], t[S + 4], cf);
                    for (int i = 0; i < n2; i++) glpgp_amg_entry_kcombine(i, cf[0], cf[1], dp + v, dp + d, dp + e);
                }
                ret = 1;
            }
            if (ret) {
                if (lev == lb) break;
                lev--; /* back into cycle(lev - 1) */
                kind = CY;
            }
        } else {
            /* cycle(lev): out <- B_lev r */
            const int r = cy_r[lev], n2 = 2 * GLPGP_BT(q, GLPGP_AMG_BT_N);
            const int bnext = GLPGP_BT(q + 1, GLPGP_AMG_BT_B), enext = GLPGP_BT(q + 1, GLPGP_AMG_BT_E);
            int buf[2];
            buf[0] = GLPGP_BT(q, GLPGP_AMG_BT_TMP);
            buf[1] = cy_out[lev];
            if (pc_cy[lev] == 0) {
                const int writes = (pre > 0 ? pre : 1) + post;
                int k = writes % 2, cur = buf[k];
                if (pre > 0) {
                    glpgp_amg_bt_smooth(q, tab, ip, dp, r, -1, cur);
                    for (int s = 1; s < pre; s++) {
                        k ^= 1;
                        glpgp_amg_bt_smooth(q, tab, ip, dp, r, cur, buf[k]);
                        cur = buf[k];
                    }
                    glpgp_amg_bt_restrict(q, tab, ip, dp, r, cur, bnext);
                } else {
                    glpgp_amg_bt_axpby(dp, t, n2, -1, -1, 0.0, cur, -1, -1, 0.0, cur);
                    glpgp_amg_bt_restrict(q, tab, ip, dp, r, -1, bnext);
                }
                cy_cur[lev] = cur;
                cy_k[lev] = k;
                pc_cy[lev] = 1;
                lev++; /* coarse_correction(lev + 1) */
                pc_cc[lev] = 0;
                kind = CC;
                continue;
            }
            int k = cy_k[lev], cur = cy_cur[lev];
            glpgp_amg_bt_prolong(q, tab, ip, dp, enext, cur);
            for (int s = 0; s < post; s++) {
                k ^= 1;
                glpgp_amg_bt_smooth(q, tab, ip, dp, r, cur, buf[k]);
                cur = buf[k];
            }
            kind = CC; /* back into coarse_correction(lev) */
        }
    }
#undef GLPGP_BT_CALL_CYCLE
    /* out <- e_lb */
    {
        const int n2 = 2 * GLPGP_BT(0, GLPGP_AMG_BT_N), e = GLPGP_BT(0, GLPGP_AMG_BT_E);
        for (int i = 0; i < n2; i++) out[i] = dp[e + i];
    }
}
