/* solver/internal.h: what the solver's files share and nobody else sees:
 * one Newton level at fixed eps (newton.c), used by the continuation, and the
 * truncated CG of the trust-region step (steihaug.c). */
#ifndef GLPGP_SOLVER_INTERNAL_H
#define GLPGP_SOLVER_INTERNAL_H

#include "glpgp/solve.h"

/* Leave a timed phase (glpgp_timer_enter / _leave of glpgp/backend.h):
 * with sync (glpgp_options.phase_sync) the device's work enqueued in it is
 * waited for first (b->ops->finish), so that the phase's time includes it. */
void glpgp_tm_leave(glpgp_backend *b, int sync, int prev);

/* Name of oscillator k ("u", "v", or "cross" for k = 2: the cross field) for messages. */
const char *glpgp_osc_name(int k);

/* One Newton level: x <- argmin E + P_eps from the state's x, modified Newton
 * steps until |g| <= rtol |g_0|, the cap o->newton_max (ls->capped), or no
 * descent. ls receives eps, counts, gradient norms and the energy. */
glpgp_status glpgp_newton_level(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *ns,
                                int k, double eps, double rtol, glpgp_level_stats *ls);

/* Why a trust-region CG run stopped. */
typedef enum glpgp_trcg_reason {
    GLPGP_TRCG_CONVERGED = 0, /* |r| <= rtol |b| inside the region (or b = 0) */
    GLPGP_TRCG_MAXIT,         /* the iteration cap: the last iterate */
    GLPGP_TRCG_BOUNDARY,      /* the CG path left the region: cut at its boundary */
    GLPGP_TRCG_NEGCURV,       /* p.Ap <= 0: followed p to the boundary (or, without a
                                 region, the last iterate / p_0) */
    GLPGP_TRCG_PRECOND        /* r.z <= 0: the preconditioner is not SPD;
                                 the last iterate is returned, use a safer Hessian */
} glpgp_trcg_reason;

typedef struct glpgp_trcg_info {
    int iterations;           /* spmv's (matrix-vector products) done */
    double relres;            /* |r| / |b| of the last full iterate */
    double norm;              /* ||x||_M of the returned step */
    int crossed;              /* look-ahead: the path left the region, xb holds the
                                 boundary point (x: the Newton step when reason is
                                 CONVERGED, else of no use) */
    glpgp_trcg_reason reason;
} glpgp_trcg_info;

/* Steihaug-Toint truncated PCG on the backend's NEWTON matrix A (need not be
 * positive definite) with the block-Jacobi preconditioner M (DINV), or, mg
 * not NULL, M^-1 = the symmetric multigrid cycle glpgp_amg_apply_spd of mg (updated
 * by glpgp_amg_update_spd): x
 * approximately minimises -rhs.x + 1/2 x.A x subject to ||x||_M <= radius
 * (radius <= 0 or infinite: no region). Starts from x = 0; stops at
 * |r| <= rtol |rhs|, on the boundary, on negative curvature (p.Ap <= 0) or
 * after maxit iterations (info->reason). xb (NULL: none): the look-ahead of
 * steihaug.c (the boundary point there, x goes on to the Newton step).
 * Uses the fused CG ops of the backend table and
 * creates its four work vectors inside; reads the scalars back once per
 * iteration. Errors: backend failures, non-finite values. */
glpgp_status glpgp_trcg(glpgp_backend *b, glpgp_amg *mg, const glpgp_vec *rhs, glpgp_vec *x,
                        double radius, double rtol, int maxit, glpgp_vec *xb, glpgp_trcg_info *info);
const char *glpgp_trcg_reason_name(glpgp_trcg_reason r);
/* The multigrid preconditioner for one system when o->precond asks for it:
 * glpgp_amg_create, or NULL after one warning line naming `what` and the
 * reason (the caller then uses Jacobi-PCG). NULL without a message when
 * o->precond is Jacobi. */
glpgp_amg *glpgp_amg_try_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                                const double *w, double h, const char *what);

/* glpgp_amg_update; on failure one warning line naming `what` and 0 (the
 * caller stops using a), else 1. */
int glpgp_amg_try_update(glpgp_amg *a, const glpgp_vec *x, const char *what);
/* the same with glpgp_amg_update_spd (the trust region's multigrid region) */
int glpgp_amg_try_update_spd(glpgp_amg *a, const glpgp_vec *x, const char *what);

/* qsort comparator: doubles in ascending order (solver/result.c) */
int glpgp_cmp_double(const void *a, const void *b);

/* ---- one rank's part of a distributed mesh (m->part; solver/distributed.c):
 * global values through the backend's reduce op, the same on every rank ---- */
/* *n <- the number of owned vertices with flag set, over all ranks */
glpgp_status glpgp_dist_count(glpgp_backend *b, const glpgp_mesh *m, const unsigned char *flag, int *n);
/* minimum, 10th percentile and median of |z| over the owned vertices of all
 * ranks (z: 2 m->nv, owned first), as glpgp_osc_summarize (NULL: not wanted) */
glpgp_status glpgp_dist_zabs_stats(glpgp_backend *b, const glpgp_mesh *m, const double *z, double *min, double *p10,
                                   double *median);
/* glpgp_osc_summarize on a part: o->singular of the local triangles, the
 * counts and |z| statistics of the whole mesh */
glpgp_status glpgp_dist_summarize(glpgp_backend *b, const glpgp_mesh *m, glpgp_osc_result *o);

/* One INFO line about a non-uniform size field (solver/sizefield.c). */
void glpgp_size_log(const glpgp_mesh *m, const double *size, double h);

#endif
