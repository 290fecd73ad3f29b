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
 *     2x2 diagonal blocks (block-Jacobi preconditioner);
 *   - optionally an aggregation multigrid hierarchy on NEWTON (the amg_* ops
 *     below): level matrices, prolongation weights, smoothers and the
 *     coarse-solve operator, all on the device.
 * Layer: solver (the interface; implementations: backends). */
#ifndef GLPGP_BACKEND_H
#define GLPGP_BACKEND_H

#include "glpgp/system.h"
#include "glpgp/timers.h"

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
    GLPGP_S_LIN,                 /* x . b of a linear energy term (glpgp_newton_state.lin) */
    GLPGP_NSLOTS = 16
};

enum glpgp_matrix { GLPGP_MAT_QUAD = 0, GLPGP_MAT_NEWTON = 1 };

/* ---- multilevel (aggregation AMG) preconditioner: data layout ------------
 * The hierarchy (built on the host by solver/amg.c, design in its header and
 * docs/numerics.md) has levels l = 0 .. L-1; level 0 is NEWTON on the system's
 * pattern, level L-1 the coarsest. Every level is a 2x2-block CSR matrix A_l
 * on n_l nodes. Node i of level l < L-1 belongs to at most one aggregate
 * agg[i] (a node of level l+1); the prolongation P_l maps the 2 unknowns of
 * coarse node J to c_i (x) on each member i, where c_i = cr + i ci is a complex
 * weight acting as the 2x2 block [[cr, -ci], [ci, cr]] (a scaled rotation).
 * The structure is uploaded once per hierarchy (amg_setup); the values (c,
 * A_l = P^T A_{l-1} P, smoothers, coarse solve) are rebuilt on the device
 * per Newton step (amg_values, amg_coarse_invert: no host round trip). */
#define GLPGP_AMG_MAX_LEVELS 24

/* Structure of level l (host arrays; the backend copies what it needs). */
typedef struct glpgp_amg_level {
    int n;             /* nodes (level 0: the system's vertices) */
    long nnzb;         /* 2x2 blocks of A_l */
    const int *rowptr; /* n + 1 (level 0: NULL, the system's pattern is used) */
    const int *col;    /* nnzb, sorted within each row, diagonal included */
    const int *diag;   /* n: slot of (i, i) */
    /* transfer to level l+1 (NULL on the coarsest level): */
    const int *agg;    /* n: aggregate of node i, -1 when i is on no coarser
                          level (Dirichlet vertex: the smoother solves its
                          identity row exactly) */
    const int *aptr;   /* n_{l+1} + 1: members of aggregate J are */
    const int *amem;   /*   amem[aptr[J] .. aptr[J+1]), increasing */
    const int *gptr;   /* nnzb_{l+1} + 1: Galerkin map (gather form): block */
    const int *gsrc;   /*   slot K of A_{l+1} sums the level-l slots
                            gsrc[gptr[K] .. gptr[K+1]), increasing */
} glpgp_amg_level;

typedef struct glpgp_amg_layout {
    int nlevels;   /* L, 2 .. GLPGP_AMG_MAX_LEVELS */
    double weight; /* smoother weight w in (0, 2): M_l^-1 below is w times the
                      inverse of the l1 block diagonal */
    glpgp_amg_level lev[GLPGP_AMG_MAX_LEVELS];
    /* the cycle of solver/amg.c, for a backend that runs whole coarse
     * corrections itself (amg_coarse_correction): sweeps before / after the
     * coarse correction, and kcycle[c] = 1 when the coarse correction on
     * level c (0 < c < L-1) is a K-cycle (0: one plain visit) */
    int pre, post;
    unsigned char kcycle[GLPGP_AMG_MAX_LEVELS];
    /* the structure this layout comes from (NULL: none): a backend that holds
     * the hierarchy of the same key, weight, sweeps and K-cycle levels keeps
     * it (no upload: the guiding field, u and v share one structure) */
    const void *key;
} glpgp_amg_layout;

/* AMG scalar registers: a device array of GLPGP_AMG_NSLOTS doubles, separate
 * from the s[] slots of the Jacobi path. Slots 0..7 belong to the outer
 * flexible CG, slots GLPGP_AMG_KSLOT(l) .. +7 to the inner Krylov steps of
 * the K-cycle on level l. */
#define GLPGP_AMG_NSLOTS (8 + 8 * GLPGP_AMG_MAX_LEVELS)
#define GLPGP_AMG_KSLOT(l) (8 + 8 * (l))
/* the status of the last amg_coarse_invert (0: fine, 1: the coarsest matrix
 * is not finite), among the outer solvers' registers and used by none */
#define GLPGP_AMG_SLOT_STATUS 7

/* A coefficient computed on the device: sign * t[num] / t[den], or 0 when
 * t[den] is 0 or the ratio is not finite; num < 0: the constant sign. */
typedef struct glpgp_amg_coef {
    int num, den;
    double sign;
} glpgp_amg_coef;

typedef struct glpgp_backend_ops {
    const char *name; /* "reference" or "opencl" */
    /* 1: setup accepts a coupled cross-field system (glpgp_system with cconj,
     * solver/coupled.c); 0: setup refuses it */
    int coupled_systems;
    void (*destroy)(glpgp_backend *b); /* frees b->impl, not b */
    /* Optional (NULL: none). *out <- a new backend with b's ops, on b's device,
     * not set up, sharing nothing the drivers write (its own queue, buffers,
     * scalars and counters): one host thread may drive it while another
     * drives b (glpgp_solve's concurrent oscillators). Read-only objects
     * (an OpenCL context and program) may be shared. */
    glpgp_status (*clone)(glpgp_backend *b, glpgp_backend **out);

    /* Upload the mesh layout (coordinates, triangles, pattern, gather maps;
     * a coupled system's matching, system.h). Called again for another
     * system, it releases the previous one's data (its matrices, multigrid;
     * vectors stay valid only if of the new size). The system must outlive
     * the backend's use of it. */
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
     * flags, 1 = fixed vertex). Resets the size field to the uniform h. */
    glpgp_status (*set_field)(glpgp_backend *b, const double *w, const unsigned char *dirichlet);
    /* Per oscillator, after set_field: per-vertex target sizes (nv doubles,
     * > 0; glpgp_size_compute) used by assemble_quadratic instead of its h
     * (kernels/element.h: glpgp_elem_scales); NULL: back to the uniform h,
     * whose arithmetic is unchanged (bit for bit). */
    glpgp_status (*set_size)(glpgp_backend *b, const double *size);
    /* QUAD <- sum over triangles of the element matrices of `kind`
     * (GLPGP_ELEM_*) with target size h (or the sizes of set_size), gathered
     * through the slot map. */
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

    /* ---- multilevel preconditioner (optional: a backend that leaves
     * amg_setup NULL gets Jacobi-PCG, with one warning). t[] below are the
     * AMG scalar registers (GLPGP_AMG_NSLOTS), l a level index, vectors of
     * level l hold 2 n_l doubles. The drivers (solver/amg.c) call: ----
     *
     * amg_setup:   upload the hierarchy structure (replaces any previous one).
     * amg_values:  per Newton step, from NEWTON (assembled) and the frame
     *   vectors frames[0 .. L-2] (level-l vectors or NULL), for l = 0 .. L-2:
     *     f_l  = frames[0] (1 when NULL), 0 at the vertices the Dirichlet
     *            flags of the last set_field mark             (l = 0)
     *     f_lJ = a_lJ (frames[l]_J, or 1 when NULL)          (l >= 1, complex)
     *     s_J  = sqrt(sum_{i in J} |f_li|^2),  a_{l+1,J} = s_J,
     *     c_i  = f_li / s_agg(i)  (0 when s = 0: J is dead),
     *     A_{l+1} = P_l^T A_l P_l through the Galerkin map; the diagonal block
     *       of a dead coarse node is the identity;
     *     M_l^-1  = w times the inverse of the l1 block diagonal
     *       A_l,ii + (sum_{j != i} ||A_l,ij||_2) I  (0 where singular);
     *       since that diagonal bounds A from above, the sweep converges for
     *       any SPD A_l when w < 2.
     * amg_coarse_invert: the coarse solve operator C from the coarsest
     *   A_{L-1} (of the last amg_values), on the backend: spd = 0 the LU
     *   generalised inverse, spd = 1 the symmetric positive semi-definite
     *   one (kernels/amg_dense.h, bit-identical on every backend);
     *   t[GLPGP_AMG_SLOT_STATUS] <- 0, or 1 when A_{L-1} is not finite (the
     *   drivers read it with their first scalars: no round trip here).
     * amg_coarse_read (optional, diagnostics): the coarsest A_{L-1} as a dense row-major matrix of
     *   order m = 2 n_{L-1} (host array of m*m doubles; synchronises).
     * amg_smooth:  y <- x + M_l^-1 (r - A_l x)   (x NULL: y <- M_l^-1 r)
     * amg_restrict: rc <- P_l^T (r - A_l x)       (x NULL: rc <- P_l^T r)
     * amg_prolong: x <- x + P_l ec
     * amg_coarse_solve: x <- C r  (coarsest level)
     * amg_spmv_dots: y <- A_l x;  t[slot] <- x.y;  t[slot+1] <- x.u;
     *   t[slot+2] <- x.w  (u, w may be NULL: that slot is left alone)
     * amg_dots:    t[slot] <- x.u;  t[slot+1] <- x.w  (u, w may be NULL)
     * amg_axpby:   y <- a x + c y  (a, c: glpgp_amg_coef; a zero coefficient
     *   does not read its vector: 0 x + 0 y clears y even if it holds NaN)
     * amg_kcombine: the K-cycle's two-step Krylov combination, from
     *   rho1 = t[slot], alpha1 = t[slot+1], beta = t[slot+2],
     *   gamma = t[slot+3], alpha2 = t[slot+4]:
     *     rho2 = beta - gamma^2 / rho1,
     *     e <- (alpha1/rho1 - gamma alpha2 / (rho1 rho2)) v + (alpha2/rho2) d,
     *   falling back to e <- (alpha1/rho1) v when rho2 <= 1e-12 |beta| or a
     *   coefficient is not finite, and to e <- 0 when rho1 is 0.
     * amg_get_scalars: host out[0..n) <- t[0..n) (synchronises).
     * amg_coarse_correction (optional, may be NULL): e <- the coarse
     *   correction of level c (1 <= c <= L-1) with right-hand side rhs
     *   (level-c vectors), computed entirely inside the backend with the
     *   sequence of solver/amg.c's coarse_correction (the layout's pre, post
     *   and kcycle; the same ops, in the same order, registers t included);
     *   sym = 1: the symmetric cycle of glpgp_amg_apply_spd instead
     *   (max(pre, post) sweeps before and after, a W-visit where the layout
     *   has a K-cycle); *done <- 0 when the backend leaves level c to the
     *   driver (nothing is done then). For devices where a launch costs more
     *   than a small level's work (the OpenCL CPU shape runs the small levels
     *   in one work-item). */
    glpgp_status (*amg_setup)(glpgp_backend *b, const glpgp_amg_layout *lay);
    glpgp_status (*amg_values)(glpgp_backend *b, const glpgp_vec *const *frames);
    glpgp_status (*amg_coarse_invert)(glpgp_backend *b, int spd);
    glpgp_status (*amg_coarse_read)(glpgp_backend *b, double *dense);
    glpgp_status (*amg_smooth)(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                               glpgp_vec *y);
    glpgp_status (*amg_restrict)(glpgp_backend *b, int l, const glpgp_vec *r, const glpgp_vec *x,
                                 glpgp_vec *rc);
    glpgp_status (*amg_prolong)(glpgp_backend *b, int l, const glpgp_vec *ec, glpgp_vec *x);
    glpgp_status (*amg_coarse_solve)(glpgp_backend *b, const glpgp_vec *r, glpgp_vec *x);
    glpgp_status (*amg_spmv_dots)(glpgp_backend *b, int l, const glpgp_vec *x, glpgp_vec *y,
                                  const glpgp_vec *u, const glpgp_vec *w, int slot);
    glpgp_status (*amg_dots)(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *u,
                             const glpgp_vec *w, int slot);
    glpgp_status (*amg_axpby)(glpgp_backend *b, glpgp_amg_coef a, const glpgp_vec *x,
                              glpgp_amg_coef c, glpgp_vec *y);
    glpgp_status (*amg_kcombine)(glpgp_backend *b, const glpgp_vec *v, const glpgp_vec *d,
                                 glpgp_vec *e, int slot);
    glpgp_status (*amg_get_scalars)(glpgp_backend *b, double *out, int n);
    glpgp_status (*amg_coarse_correction)(glpgp_backend *b, int c, int sym, const glpgp_vec *rhs,
                                          glpgp_vec *e, int *done);
    /* Fused halves of a level visit (optional, NULL: the driver calls the
     * single ops; the same bits either way, kernels/amg_rows.h):
     * amg_presmooth_restrict: y <- M_l^-1 r and rc <- P_l^T (r - A_l y), i.e.
     *   amg_smooth (x NULL) then amg_restrict (x = y), l < L-1;
     * amg_prolong_smooth: y <- x' + M_l^-1 (r - A_l x') with x' = x + P_l ec,
     *   i.e. amg_prolong into a copy of x then amg_smooth; x is not changed. */
    glpgp_status (*amg_presmooth_restrict)(glpgp_backend *b, int l, const glpgp_vec *r, glpgp_vec *y,
                                           glpgp_vec *rc);
    glpgp_status (*amg_prolong_smooth)(glpgp_backend *b, int l, const glpgp_vec *ec, const glpgp_vec *x,
                                       const glpgp_vec *r, glpgp_vec *y);

    /* ---- whole linear solve (optional, NULL: the drivers' CG / multigrid):
     * x <- NEWTON^-1 rhs from x = 0 by the backend's own Krylov solver and
     * preconditioner, stopping at |r| <= rtol |rhs| (unpreconditioned
     * residual) or after maxit iterations. *iterations, *relres <- what was
     * done; *reason <- 0 converged, 1 the cap, 2 breakdown (not SPD, non-
     * finite): the values of glpgp_cg_reason (glpgp/solve.h). A backend with
     * this op gets no host multigrid (amg_setup stays NULL): glpgp_linear_solve
     * calls it whatever the preconditioner option, which the backend was
     * created with (the PETSc backend: KSPCG + GAMG or point-block Jacobi). */
    glpgp_status (*linear_solve)(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol,
                                 int maxit, int *iterations, double *relres, int *reason);

    /* ---- distributed meshes (optional, NULL: one process): the driver's
     * reductions of host values over the ranks of a mesh that is one rank's
     * part (glpgp_mesh.part): v[0 .. n) <- the sum (GLPGP_REDUCE_SUM, the
     * same bits on every rank), maximum or minimum over the ranks; every
     * rank calls it alike. */
    glpgp_status (*reduce)(glpgp_backend *b, double *v, int n, int op);

    /* ---- optional (NULL: the drivers do without) ----
     * finish: block until every operation enqueued so far is done (the
     *   phase accounts of glpgp_options.phase_sync; a synchronous backend
     *   leaves it NULL).
     * trial_point: the trust region's trial point xt <- x (+) a d, per vertex
     *   glpgp_polar_point of kernels/newton_rows.h with retract radius r1
     *   (a polar update outside vortex cores, the straight one inside);
     *   required for glpgp_options.retract_zabs > 0 (the default). */
    glpgp_status (*finish)(glpgp_backend *b);
    glpgp_status (*trial_point)(glpgp_backend *b, const glpgp_vec *x, const glpgp_vec *d, double a,
                                double r1, glpgp_vec *xt);
} glpgp_backend_ops;

enum { GLPGP_REDUCE_SUM = 0, GLPGP_REDUCE_MAX = 1, GLPGP_REDUCE_MIN = 2 };

#define GLPGP_SCRATCH_VECTORS 8

struct glpgp_backend {
    const glpgp_backend_ops *ops;
    void *impl;               /* backend-private state */
    const glpgp_system *sys;  /* set by setup */
    /* counters for stats and benchmarks (incremented by the drivers; n_launch,
     * device kernel launches, by the OpenCL backend: on a GPU each costs a few
     * microseconds of host time however small the kernel) */
    long n_spmv, n_cg_iter, n_sync, n_launch;
    /* 1: a kernel launch costs microseconds of host time whatever its size (the
     * OpenCL backend's GPU launch shape): the multigrid then keeps its K-cycle
     * to the large levels (glpgp_amg_kcycle_min); set by the backend */
    int launch_bound;
    /* what glpgp_solve's auto mode (glpgp_options.oscillators) expects from
     * running the second oscillator on a clone beside this backend: set by
     * the backend, copied by clone */
    int overlap;
    /* where the time goes (glpgp/timers.h): the phase accounts, the phase
     * being timed and since when (glpgp_timer_enter / _leave below); the
     * backend adds its blocking waits to the current phase (glpgp_backend_waited) */
    glpgp_timers tm;
    int tm_cur;
    double tm_mark;
    /* the multigrid structure of the system being solved, built once by
     * glpgp_solve and used by every glpgp_amg_create on it (borrowed; NULL:
     * none, each hierarchy builds its own) */
    const struct glpgp_amg_structure *amg_shared;
    /* the drivers' scratch vectors (glpgp_backend_scratch), kept between calls:
     * a linear solve creates none of its own */
    glpgp_vec *scratch[GLPGP_SCRATCH_VECTORS];
    size_t scratch_n[GLPGP_SCRATCH_VECTORS];
};

enum {
    GLPGP_OVERLAP_NEVER = 0,  /* not measured to pay (PETSc) */
    GLPGP_OVERLAP_ALWAYS = 1, /* a single-threaded backend (reference): up to 2x; the OpenCL
                                 GPU launch shape (H200, 1M square: 1.48x) */
    GLPGP_OVERLAP_AMG = 2     /* with the multigrid and up to GLPGP_OVERLAP_AMG_MAX_VERTICES
                                 only: the OpenCL CPU shape, whose fused small levels run on
                                 one core (2 cores, bench/results/oscillators.md: 1.25x at
                                 107k vertices, 1.2x at 64k, 1.0-1.06x at 250k, 1.0x at 1M,
                                 where the per-op levels dominate); its Jacobi-CG keeps every
                                 core busy (two at once: 0.67-1.0x) */
};
#define GLPGP_OVERLAP_AMG_MAX_VERTICES 500000

/* *v <- b's scratch vector k (0 .. GLPGP_SCRATCH_VECTORS - 1) of n doubles,
 * created at its first use or when n changes; its contents are undefined.
 * CG uses 0 .. 3, the trust region's CG 4 .. 7. Freed by
 * glpgp_backend_destroy. */
glpgp_status glpgp_backend_scratch(glpgp_backend *b, int k, size_t n, glpgp_vec **v);

/* 1 when two layouts have the same non-NULL key, levels (nodes and blocks),
 * weight, sweeps and K-cycle levels: a backend holding a's hierarchy may
 * keep it for b (solver/backend.c). */
int glpgp_amg_layout_same(const glpgp_amg_layout *a, const glpgp_amg_layout *b);

/* Destroy any backend (NULL-safe, sets *b = NULL). */
void glpgp_backend_destroy(glpgp_backend **b);

/* ---- phase accounts (glpgp/timers.h; solver/backend.c) ----
 * reset: every account to 0, the current phase GLPGP_TM_OTHER from now.
 * enter: the time since the last mark is booked to the current phase, which
 *   becomes id; returns the previous one for leave. Inside the guiding field
 *   or the size field (their own solves) only the structure phase is booked
 *   apart: enter then keeps the current phase.
 * leave: the time since the last mark is booked to the current phase, which
 *   becomes prev.
 * waited: seconds the host just spent blocked on the device, added to the
 *   current phase's wait (by the backends' blocking calls).
 * read: *t <- the accounts, the current phase's time so far included. */
void glpgp_timer_reset(glpgp_backend *b);
int glpgp_timer_enter(glpgp_backend *b, int id);
void glpgp_timer_leave(glpgp_backend *b, int prev);
void glpgp_backend_waited(glpgp_backend *b, double seconds);
void glpgp_timer_read(glpgp_backend *b, glpgp_timers *t);

#ifdef __cplusplus
}
#endif

#endif
