/* glpgp/backend.h: the small operation table that the Newton and CG drivers
 * (solver/newton.c, solver/cg.c) are written against, once. The
 * implementations live in the backends layer (glpgp/backends.h): the scalar C
 * reference (backends/reference.c) and OpenCL (backends/opencl.c). Every vector
 * and matrix lives in the backend ("device") between calls; the driver only
 * reads back the few scalars it needs (scalar slots, see glpgp_slot).
 *
 * Layout conventions (shared with system.h / kernels/element.h):
 *   - oscillator vectors hold 2*nv doubles, [Re z_i, Im z_i] per vertex i;
 *   - matrices are 2x2-block CSR on the system's pattern, 4 doubles a block;
 *   - two matrices live in the backend: QUAD (the quadratic form H_E of the
 *     current element kind, no Dirichlet handling, so grad E = QUAD x) and
 *     NEWTON (QUAD + penalty Hessian, with the Dirichlet rows and columns
 *     replaced by identity rows/columns), plus DINV, the inverses of NEWTON's
 *     2x2 diagonal blocks (block-Jacobi preconditioner).
 * Layer: solver (the interface; implementations: backends). */
#ifndef GLPGP_BACKEND_H
#define GLPGP_BACKEND_H

#include "glpgp/system.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct glpgp_backend glpgp_backend;
typedef struct glpgp_vec glpgp_vec; /* opaque: each backend defines its own */

/* Device-side scalar registers written by reductions and read by fused kernels. */
enum glpgp_slot {
    GLPGP_S_RZ0 = 0, GLPGP_S_RZ1, /* r.z of the current / next CG iteration (swapped) */
    GLPGP_S_PQ,                  /* p.Ap */
    GLPGP_S_RR,                  /* r.r */
    GLPGP_S_E,                   /* quadratic energy 1/2 x.QUAD x */
    GLPGP_S_P,                   /* penalty energy */
    GLPGP_S_DOT,                 /* scratch for dot products */
    GLPGP_S_DOT2,
    GLPGP_NSLOTS = 16
};

enum glpgp_matrix { GLPGP_MAT_QUAD = 0, GLPGP_MAT_NEWTON = 1 };

typedef struct glpgp_backend_ops {
    const char *name; /* "reference" or "opencl" */
    void (*destroy)(glpgp_backend *b); /* frees b->impl, not b */

    /* Upload the mesh layout (coordinates, triangles, pattern, gather maps).
     * Called once; the system must outlive the backend's use of it. */
    glpgp_status (*setup)(glpgp_backend *b, const glpgp_system *sys);

    /* Vectors of n doubles, zero-initialised. */
    glpgp_status (*vec_create)(glpgp_backend *b, size_t n, glpgp_vec **v);
    void (*vec_destroy)(glpgp_backend *b, glpgp_vec **v);
    glpgp_status (*vec_write)(glpgp_backend *b, glpgp_vec *v, const double *host);
    glpgp_status (*vec_read)(glpgp_backend *b, const glpgp_vec *v, double *host);
    glpgp_status (*copy)(glpgp_backend *b, glpgp_vec *dst, const glpgp_vec *src);
    /* y <- a x + c y */
    glpgp_status (*axpby)(glpgp_backend *b, double a, const glpgp_vec *x, double c, glpgp_vec *y);
    /* s[slot] <- x . y */
    glpgp_status (*dot)(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *y, int slot);
    /* host out[0..n) <- s[0..n) (synchronises) */
    glpgp_status (*get_scalars)(glpgp_backend *b, double *out, int n);

    /* Per oscillator: unit field W (2*nv doubles) and Dirichlet mask (nv
     * flags, 1 = fixed vertex). */
    glpgp_status (*set_field)(glpgp_backend *b, const double *w, const unsigned char *dirichlet);
    /* QUAD <- sum over triangles of the element matrices of `kind`
     * (GLPGP_ELEM_*) with target size h, gathered through the slot map. */
    glpgp_status (*assemble_quadratic)(glpgp_backend *b, int kind, double h);
    /* NEWTON <- QUAD + penalty Hessian variant `hess` (GLPGP_HESS_*) at x with
     * weight inv4e2 = 1/(4 eps^2) (0: no penalty); Dirichlet rows/cols ->
     * identity; DINV <- inverse of each 2x2 diagonal block of NEWTON. */
    glpgp_status (*assemble_newton)(glpgp_backend *b, const glpgp_vec *x, double inv4e2, int hess);
    /* g <- QUAD x + grad P(x), zeroed at Dirichlet vertices;
     * s[GLPGP_S_E] <- 1/2 x . QUAD x;  s[GLPGP_S_P] <- P(x). */
    glpgp_status (*gradient)(glpgp_backend *b, const glpgp_vec *x, double inv4e2, glpgp_vec *g);
    /* s[GLPGP_S_E] <- 1/2 x . QUAD x;  s[GLPGP_S_P] <- P(x)  (work: scratch vector). */
    glpgp_status (*energy)(glpgp_backend *b, const glpgp_vec *x, double inv4e2, glpgp_vec *work);
    /* y <- M x for M = QUAD or NEWTON */
    glpgp_status (*spmv)(glpgp_backend *b, int matrix, const glpgp_vec *x, glpgp_vec *y);

    /* Fused Jacobi-PCG pieces on NEWTON / DINV (alpha, beta stay on the device):
     * precond:   z <- DINV r;  s[rz] <- r.z;  s[GLPGP_S_RR] <- r.r
     * spmv_dot:  q <- NEWTON p;  s[GLPGP_S_PQ] <- p.q
     * update:    alpha = s[rz]/s[GLPGP_S_PQ];  x += alpha p;  r -= alpha q;
     *            z <- DINV r;  s[rz_new] <- r.z;  s[GLPGP_S_RR] <- r.r
     * direction: p <- z + (s[rz_new]/s[rz]) p */
    glpgp_status (*cg_precond)(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *z, int rz);
    glpgp_status (*cg_spmv_dot)(glpgp_backend *b, const glpgp_vec *p, glpgp_vec *q);
    glpgp_status (*cg_update)(glpgp_backend *b, glpgp_vec *x, glpgp_vec *r, const glpgp_vec *p,
                              const glpgp_vec *q, glpgp_vec *z, int rz, int rz_new);
    glpgp_status (*cg_direction)(glpgp_backend *b, glpgp_vec *p, const glpgp_vec *z, int rz_new, int rz);
} glpgp_backend_ops;

struct glpgp_backend {
    const glpgp_backend_ops *ops;
    void *impl;               /* backend-private state */
    const glpgp_system *sys;  /* set by setup */
    /* counters for stats and benchmarks (incremented by the drivers) */
    long n_spmv, n_cg_iter, n_sync;
};

/* Destroy any backend (NULL-safe, sets *b = NULL). */
void glpgp_backend_destroy(glpgp_backend **b);

#ifdef __cplusplus
}
#endif

#endif
