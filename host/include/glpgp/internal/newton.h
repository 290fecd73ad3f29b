/* glpgp/internal/newton.h: the solver's lower-level pieces behind
 * glpgp_solve (glpgp/solve.h), for the backends, crosscheck, the tests and
 * the benchmark: the guiding field's steps, the Dirichlet set, one Newton
 * step, CG, the aggregation multigrid and the linear solve. Internal: not
 * installed, no stability promise. Layer: solver. */
#ifndef GLPGP_INTERNAL_NEWTON_H
#define GLPGP_INTERNAL_NEWTON_H

#include "glpgp/backend.h"
#include "glpgp/solve.h"

#ifdef __cplusplus
extern "C" {
#endif


/* What the rank holding the whole mesh m computes before splitting it
 * (glpgp_mesh_extract_part): the guiding field u (2 m->nv) where it is known
 * without a solve -- radial: everywhere; boundary: at the boundary vertices
 * (fixed there by the harmonic solve), (1, 0) inside -- which is all the
 * size field (glpgp_size_compute) reads of it, and m's area centroid. */
void glpgp_field_presolve(const glpgp_mesh *m, const glpgp_options *o, double *u, double center[2]);

/* Guiding field U (2*nv) for option o (boundary/radial/file). */
glpgp_status glpgp_field_compute(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                 double *u, long *cg_iterations);
/* Dirichlet flags of oscillator field w (2*nv): boundary vertices where, for
 * one of the two adjacent boundary edges, |w.n| >= |w.t|. Returns the count. */
int glpgp_dirichlet_set(const glpgp_mesh *m, const double *w, unsigned char *dir);

/* The Newton steps a level runs before its stall test (ftol) may end it: a
 * level that converges in fewer keeps its result (an earlier stop moved the
 * sphere's singularities and raised its quads' irregular vertices:
 * bench/results/cross_stall.md). */
#define GLPGP_STALL_STEPS 20

/* State of the Newton iteration at one eps level (vectors of 2*nv doubles). */
typedef struct glpgp_newton_state {
    glpgp_vec *x;    /* iterate (updated by a step) */
    glpgp_vec *g;    /* gradient of E + P at x (input of a step) */
    glpgp_vec *d, *xt, *work; /* scratch */
    double grad0;    /* |g| at the start of the level */
    int near;        /* exact-Hessian switch of `mixed` (start at 0) */
    int cooldown;    /* steps left before `mixed` may try the exact Hessian again */
    double radius;   /* trust region radius (<= 0: none yet, the next step is a plain
                        Newton step; set from it). Kept from level to level. */
    double noise;    /* rounding level of F = E + P at x (set by the level loop; a
                        step whose predicted decrease is below it ends the level) */
    struct glpgp_amg *amg; /* multigrid preconditioner (borrowed; NULL: Jacobi) */
    int inside;      /* trust region: the region was inactive at the last step (set by the
                        step, cleared at each level start): the multigrid may try */
    double target;   /* the level's gradient target rtol |g_0| (set by the level loop on
                        the last eps level; 0: none): the inexact-Newton tolerance needs
                        no more than 0.1 target / |g| (solver/newton.c, newton_eta) */
    double ftol;     /* > 0: the level also ends when, from GLPGP_STALL_STEPS steps on,
                        E + P fell by at most ftol |E + P| over the last 3 Newton steps
                        (the stall test: --cross-ftol for the cross field,
                        --newton-ftol for the oscillators; 0: off) */
    glpgp_vec *lin;  /* NULL, or b of a linear term: F = E + P - b . x, the gradient
                        g - b (b zero at Dirichlet vertices; the Hessian unchanged: the
                        surface cross field's curvature alignment) */
    const int *stop; /* NULL, or a flag another thread may set (read atomically before
                        each step): non-zero ends the level with an error at once (the
                        other oscillator of a concurrent solve failed) */
} glpgp_newton_state;

typedef struct glpgp_newton_step_info {
    int cg;          /* CG iterations (all attempts) */
    int at_noise;    /* the model decrease (trust region: of the trial step; line search: of
                        the full Newton step) was below F's rounding level: the level is done */
    double rho;      /* trust region: actual / predicted decrease */
    double step;     /* trust region: ||d||_M of the step tried */
    double radius;   /* trust region: the radius after the step */
    int reason;      /* trust region: why its CG stopped (solver/internal.h) */
    int fallbacks;   /* Hessians abandoned for a safer one */
    int accepted;    /* the line search found a descent step */
    double alpha;    /* accepted step length (0 when none) */
    double energy;   /* E + P at the new x */
    int cg_capped;   /* CG runs of this step stopped by the cap o->cg_max */
    int amg_step;    /* trust region: the step taken is the multigrid inexact Newton step */
    int amg_rejected;/* trust region: multigrid candidates given up for the Steihaug step
                        (FCG met p.Ap <= 0 or its cap, or rho < tr_poor) */
    int lookahead_step;     /* trust region: the step taken is the Newton step beyond the region */
    int lookahead_rejected; /* trust region: look-ahead Newton steps given up (rho < tr_poor) */
    int resolves;    /* trust region: region subproblems solved again in a smaller region
                        (o->tr_resolve) */
} glpgp_newton_step_info;

/* One Newton step at x. Line search: assemble (H_E + H~_P(x)), solve it by
 * PCG to the inexact-Newton tolerance (Jacobi, or flexible CG with s->amg,
 * whose values are rebuilt from the new matrix and x), backtrack on E + P,
 * update x. Trust region: assemble the exact Hessian, Steihaug-CG in the
 * region s->radius (preconditioner and norm: block Jacobi, or with s->amg
 * and o->tr_precond AMG the symmetric multigrid cycle built on the projected
 * Hessian, glpgp_amg_apply_spd: Steihaug-Toint needs a fixed SPD
 * preconditioner, the K-cycle is not one; with s->amg and s->inside, the
 * region inactive, first the K-cycle FCG inexact Newton step, kept when its
 * full step has rho >= tr_poor), take the trial point x (+) a d (polar update, retract_zabs) with a = 1
 * (a step cut by the region whose full step fails or is poor is solved again in a smaller
 * region on the same Hessian, up to o->tr_resolve times) or backtracked until the actual decrease is at least tr_accept of the
 * predicted one, update the radius. Needs QUAD assembled and
 * s->g = grad(E+P)(x) with F = (E+P)(x) and gn = |g| (and, for the trust
 * region, s->noise). */
/* ns->g <- the gradient of F at ns->x (with ns->lin's term; its b . x
 * then in slot GLPGP_S_LIN, the energies in GLPGP_S_E and GLPGP_S_P) */
glpgp_status glpgp_newton_gradient(glpgp_backend *b, glpgp_newton_state *ns, double inv4e2);
/* F = E + P (- b . x) from the slots s read after glpgp_newton_gradient */
double glpgp_newton_energy(const glpgp_newton_state *ns, const double *s);

glpgp_status glpgp_newton_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *s,
                               double inv4e2, double F, double gn, glpgp_newton_step_info *info);

/* Why a CG run stopped. */
typedef enum glpgp_cg_reason {
    GLPGP_CG_CONVERGED = 0, /* |r| <= rtol |b| (or b = 0) */
    GLPGP_CG_MAXIT,         /* the iteration cap was reached */
    GLPGP_CG_BREAKDOWN      /* p.Ap <= 0 or a non-finite residual: not SPD */
} glpgp_cg_reason;

/* Outcome of one CG run. */
typedef struct glpgp_cg_info {
    int iterations;
    double relres;          /* |r| / |b| at the last check */
    glpgp_cg_reason reason;
} glpgp_cg_info;

/* The end of a CG loop (cg.c; shared by the Jacobi-PCG and the flexible CG
 * of the multigrid): k iterations done (k > maxit: the cap was hit), rel the
 * last relative residual; sets info->reason (MAXIT at the cap unless
 * converged) and info->relres and returns the iteration count (<= maxit). */
int glpgp_cg_verdict(glpgp_cg_info *info, int k, int maxit, double rel, double rtol);

/* Jacobi-PCG on the backend's NEWTON matrix: solves NEWTON x = rhs from x = 0.
 * A breakdown or the cap is not an error: it is reported in info->reason
 * (GLPGP_OK returned); errors are backend failures and a non-finite rhs.
 * Work vectors are created and destroyed inside. */
glpgp_status glpgp_cg(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol,
                      int maxit, int check, glpgp_cg_info *info);

/* ---- aggregation multigrid preconditioner (solver/amg.c) ----
 * Structure once per (mesh, Dirichlet set): aggregates of about 4 vertices
 * per level from two passes of pairwise matching on the vertex graph
 * (Dirichlet vertices excluded), the coarse patterns and the Galerkin index
 * maps, uploaded to the backend. Values per Newton step (glpgp_amg_update):
 * the prolongation maps each aggregate's 2 coarse unknowns to the current
 * oscillator's frame (so [z, iz] is reproduced exactly), A_c = P^T A P,
 * l1-Jacobi smoothers and a dense inverse of the coarsest matrix. Applied as
 * a K-cycle inside flexible CG (glpgp_fcg). Design: docs/numerics.md. */
typedef struct glpgp_amg glpgp_amg;

/* Hierarchy facts for logs, tests and the benchmark. */
typedef struct glpgp_amg_info {
    int nlevels;
    int n[GLPGP_AMG_MAX_LEVELS];      /* nodes per level */
    long nnzb[GLPGP_AMG_MAX_LEVELS];  /* 2x2 blocks per level */
    double operator_complexity;       /* sum_l nnzb_l / nnzb_0 */
    double grid_complexity;           /* sum_l n_l / n_0 */
    double seconds_structure;         /* glpgp_amg_create (the structure's construction when not shared) */
    int shared;                       /* 1: the structure was the system's shared one
                                         (glpgp_backend.amg_shared), built once */
    double seconds_values;            /* all glpgp_amg_update calls */
    double seconds_coarse;            /* of which the coarsest inverse on the host */
    int updates;                      /* glpgp_amg_update calls */
} glpgp_amg_info;

/* The hierarchy's structure for one system: aggregates of every level
 * (every vertex aggregated: the Dirichlet sets of the guiding field, u and v
 * enter only the values), coarse patterns and Galerkin maps, built once
 * with o->amg_coarse and o->amg_max_levels and shared read-only by every
 * glpgp_amg_create on a backend set up for that system whose
 * glpgp_backend.amg_shared points to it (glpgp_solve does this for the
 * guiding field, u, v and a concurrent v's backend clone). */
typedef struct glpgp_amg_structure glpgp_amg_structure;
glpgp_status glpgp_amg_structure_create(const glpgp_system *sys, const glpgp_options *o,
                                        glpgp_amg_structure **out);
void glpgp_amg_structure_destroy(glpgp_amg_structure **s);

/* Whether backend b implements the multigrid ops (amg_setup etc.). */
int glpgp_amg_supported(const glpgp_backend *b);

/* Levels with at least this many nodes get the K-cycle's two Krylov steps,
 * smaller ones a plain visit, on a backend whose kernel launches cost
 * microseconds of host time (b->launch_bound: an OpenCL GPU). The K-cycle
 * visits level l 2^l times, ~10 launches each: 2170 launches per cycle at 1M
 * vertices (9 levels), 12.9 ms per iteration on an H200 against 0.2 ms for a
 * Jacobi-CG iteration; from 2000 nodes down a plain visit cuts the launches
 * 4x at the same iteration counts to within one (docs/numerics.md). */
#define GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND 2000

/* The K-cycle threshold in effect: o->amg_kcycle_min where >= 0, else (-1,
 * the default) 0 (K-cycle on every level) on a backend with cheap launches
 * and GLPGP_AMG_KCYCLE_MIN_LAUNCH_BOUND on a launch-bound one. */
int glpgp_amg_kcycle_min(const glpgp_backend *b, const glpgp_options *o);

/* The hierarchy for b's system (b->ops->setup done): its structure (the
 * shared one, b->amg_shared, when it was built for this system with the
 * same o->amg_coarse and o->amg_max_levels; else built here), uploaded
 * unless the backend holds it already. The frames vanish at the Dirichlet
 * flags of the backend's last set_field (dir: those flags, kept for the
 * callers; not read). Options: o->amg_*.
 * w (2*nv unit field, may be NULL) and h: the plane-wave frames
 * exp(i (2 pi / h) W . (x_i - x_J)) used by glpgp_amg_update(a, NULL) for the
 * quadratic problems (naive PGP); w NULL or h <= 0: constant frames (the
 * Laplacian of the guiding field). GLPGP_ERR_UNSUPPORTED when the backend
 * has no multigrid ops. */
glpgp_status glpgp_amg_create(glpgp_backend *b, const glpgp_options *o, const unsigned char *dir,
                              const double *w, double h, glpgp_amg **out);
void glpgp_amg_destroy(glpgp_amg **a);

/* Rebuild the values from the backend's current NEWTON matrix: frames from
 * the oscillator x (2*nv on the device: the Newton iterate) or, x NULL, the
 * plane-wave / constant frames given at creation. Fails (GLPGP_ERR_NUMERIC)
 * when the coarsest matrix has no usable inverse. */
glpgp_status glpgp_amg_update(glpgp_amg *a, const glpgp_vec *x);

/* glpgp_amg_update for glpgp_amg_apply_spd: the same values, but the
 * coarsest operator is a symmetric positive semi-definite generalised
 * inverse (symmetric part, pivoted L D L^T, |D|^-1: the inverse for a
 * nonsingular PSD A_c) instead of the LU inverse, so that the
 * symmetric cycle (glpgp_amg_apply_spd) is a fixed symmetric positive
 * (semi-)definite operator.
 * The trust region calls it with a positive semi-definite NEWTON (the
 * projected Hessian) and then reassembles the exact one. */
glpgp_status glpgp_amg_update_spd(glpgp_amg *a, const glpgp_vec *x);

/* Hierarchy facts (valid after glpgp_amg_create). */
void glpgp_amg_get_info(const glpgp_amg *a, glpgp_amg_info *info);

/* One application of the preconditioner: z <- B r (a K- or V-cycle from
 * z = 0 on level 0; r, z: 2*nv on the device). For tests. */
glpgp_status glpgp_amg_apply(glpgp_amg *a, const glpgp_vec *r, glpgp_vec *z);

/* z <- B r by the symmetric multigrid cycle: max(amg_pre, amg_post)
 * l1-Jacobi sweeps before and after each coarse correction; where the
 * K-cycle would make two Krylov steps on a coarse level (amg_cycle,
 * amg_kcycle_min) a W-visit instead (two stationary steps of the cycle
 * there: e = (2 B_c - B_c A_c B_c) b), elsewhere a plain visit; the
 * coarsest operator of the last update. B is a fixed linear operator,
 * symmetric when the coarsest operator is (glpgp_amg_update_spd), and
 * positive definite when in addition 2 M_l / w - A_l > 0 on every level and
 * the coarse levels are positive semi-definite (l1-Jacobi with w < 2 on the
 * hierarchy of a positive semi-definite matrix; level 0's A may then be any
 * symmetric matrix below the one the hierarchy was built from). The preconditioner and norm of the trust region's Steihaug-Toint
 * CG (glpgp_options.tr_precond). */
glpgp_status glpgp_amg_apply_spd(glpgp_amg *a, const glpgp_vec *r, glpgp_vec *z);

/* Flexible CG (FCG(1), Notay) on NEWTON with the multigrid preconditioner a
 * (glpgp_amg_update done for the current NEWTON): solves NEWTON x = rhs from
 * x = 0, same contract as glpgp_cg (breakdown: p.Ap <= 0 or a non-finite
 * residual; the cap is min(maxit, o->amg_maxit)); the residual is read back
 * every o->amg_check iterations. */
glpgp_status glpgp_fcg(glpgp_amg *a, const glpgp_vec *rhs, glpgp_vec *x, double rtol, int maxit,
                       glpgp_cg_info *info);

/* The linear solve the drivers use: glpgp_fcg when a is not NULL, else
 * glpgp_cg. */
glpgp_status glpgp_linear_solve(glpgp_backend *b, glpgp_amg *a, const glpgp_vec *rhs,
                                glpgp_vec *x, double rtol, int maxit, int check,
                                glpgp_cg_info *info);

#ifdef __cplusplus
}
#endif

#endif
