/* backend_common.cl: shared pieces of the OpenCL kernels of host/backends/opencl.c:
 * the fp64 pragma, the work-item -> index-range mapping (one kernel source
 * serves both launch shapes) and the deterministic work-group reductions.
 *
 * The kernel files are concatenated after glpgp/kinds.h, kernels/element.h and
 * kernels/rows.h into one program (see kernels/embed.cmake); every per-row body
 * lives in rows.h, shared with the C reference (host/backends/reference.c).
 * The host also prepends the fp64 and FP_CONTRACT pragmas so that arithmetic
 * is compiled exactly as written (no fused multiply-add), which keeps per-row
 * results bit-identical to the reference.
 *
 * Launch shapes (chosen by the host from the device type):
 *   - CPU devices: ~128 work-items, local size 1 (GLPGP_WG = 1), each owning
 *     the contiguous index range [gid*chunk, gid*chunk + chunk) of the rows;
 *   - GPUs: one index per work-item (chunk = 1), local size GLPGP_WG
 *     (power of two), local-memory tree reductions.
 * Reductions are two-stage: every work-group writes its partial sum to
 * part[group] and glpgp_finalize sums the partials, in a fixed order, into the
 * device scalar registers s[] (backend.h's glpgp_slot). */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

#ifndef GLPGP_WG
#define GLPGP_WG 1
#endif

/* Every kernel is launched with local size GLPGP_WG. */
#define GLPGP_KERNEL __kernel __attribute__((reqd_work_group_size(GLPGP_WG, 1, 1)))

/* [lo, hi): the indices owned by this work-item out of [0, n). */
#define GLPGP_RANGE(lo, hi, n, chunk)                    \
    const int lo = (int)get_global_id(0) * (chunk);      \
    const int hi = min(lo + (chunk), (n))

/* Work-group sum of v -> out[group] (buf: GLPGP_WG doubles of local memory).
 * Tree order is fixed, so the result is deterministic for a given shape. */
void glpgp_group_sum(double v, __local double *buf, __global double *out)
{
#if GLPGP_WG == 1
    (void)buf;
    out[get_group_id(0)] = v;
#else
    const int l = (int)get_local_id(0);
    buf[l] = v;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int s = GLPGP_WG / 2; s > 0; s >>= 1) {
        if (l < s) buf[l] += buf[l + s];
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (l == 0) out[get_group_id(0)] = buf[0];
#endif
}

/* Two sums at once: v0 -> out0[group], v1 -> out1[group] (buf: 2*GLPGP_WG). */
void glpgp_group_sum2(double v0, double v1, __local double *buf, __global double *out0,
                      __global double *out1)
{
#if GLPGP_WG == 1
    (void)buf;
    out0[get_group_id(0)] = v0;
    out1[get_group_id(0)] = v1;
#else
    const int l = (int)get_local_id(0);
    buf[l] = v0;
    buf[GLPGP_WG + l] = v1;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int s = GLPGP_WG / 2; s > 0; s >>= 1) {
        if (l < s) {
            buf[l] += buf[l + s];
            buf[GLPGP_WG + l] += buf[GLPGP_WG + l + s];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    if (l == 0) {
        out0[get_group_id(0)] = buf[0];
        out1[get_group_id(0)] = buf[GLPGP_WG];
    }
#endif
}

/* Second reduction stage, launched as ONE work-group of GLPGP_WG items:
 *   s[slot0] <- scale0 * sum_{g < np0} part[g]
 *   s[slot1] <- scale1 * sum_{g < np1} part[off1 + g]     (when slot1 >= 0)
 * Work-item l sums the partials l, l + WG, l + 2 WG, ... then a tree. */
GLPGP_KERNEL void glpgp_finalize(__global const double *part, int np0, int off1, int np1,
                                 double scale0, double scale1, __global double *s, int slot0,
                                 int slot1)
{
    __local double buf[2 * GLPGP_WG];
    const int l = (int)get_local_id(0);
    double a = 0.0, b = 0.0;
    for (int g = l; g < np0; g += GLPGP_WG) a += part[g];
    for (int g = l; g < np1; g += GLPGP_WG) b += part[off1 + g];
#if GLPGP_WG > 1
    buf[l] = a;
    buf[GLPGP_WG + l] = b;
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int h = GLPGP_WG / 2; h > 0; h >>= 1) {
        if (l < h) {
            buf[l] += buf[l + h];
            buf[GLPGP_WG + l] += buf[GLPGP_WG + l + h];
        }
        barrier(CLK_LOCAL_MEM_FENCE);
    }
    a = buf[0];
    b = buf[GLPGP_WG];
#else
    (void)buf;
#endif
    if (l == 0) {
        s[slot0] = scale0 * a;
        if (slot1 >= 0) s[slot1] = scale1 * b;
    }
}
