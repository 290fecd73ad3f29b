/* solver/internal.h: what the solver's files share and nobody else sees:
 * one Newton level at fixed eps (newton.c), used by the continuation, and the
 * truncated CG of the trust-region step (steihaug.c). */
#ifndef GLPGP_SOLVER_INTERNAL_H
#define GLPGP_SOLVER_INTERNAL_H

#include "glpgp/solve.h"
#include "glpgp/surface.h"
#include "glpgp/internal/newton.h"

/* Leave a timed phase (glpgp_timer_enter / _leave of glpgp/backend.h):
 * with sync (glpgp_options.phase_sync) the device's work enqueued in it is
 * waited for first (b->ops->finish), so that the phase's time includes it. */
void glpgp_tm_leave(glpgp_backend *b, int sync, int prev);

/* The local size field of glpgp_size_compute (sizefield.c) without its
 * progress line; clamp: auto / iso limited to what m resolves (*raised: how
 * many vertices were raised; may be NULL). */
glpgp_status glpgp_size_compute_field(const glpgp_mesh *m, const glpgp_options *o, double h, const double *u,
                                      double *size, int *uniform, int clamp, int *raised);
/* Triangle t's local resolution: (its corners' smallest size over both
 * oscillators) / its longest edge (*lmax; may be NULL). */
double glpgp_size_tri_resolution(const glpgp_mesh *m, const double *size, int t, double *lmax);
/* A size file (--size-field FILE): one "h" or "h_u h_v" line per vertex of m
 * (as many numbers on every line as on the first) into size[0 .. nv) (u) and
 * size[nv .. 2 nv) (v) (sizefield.c; the plane's and the surfaces'). */
glpgp_status glpgp_size_file_read(const glpgp_mesh *m, const char *path, double *size);

/* Vertex v's cross fixed to the mean of the directions a1 and a2 (angles in
 * its frame) along the shorter arc of their crosses (surface_cross.c; the
 * rule of glpgp_surface_constraints_create). */
struct glpgp_surface_constraints;
void glpgp_surface_fix_cross(struct glpgp_surface_constraints *c, int v, double a1, double a2);

/* A surface's local size before the limit of what the mesh resolves
 * (surface_size.c; glpgp_surface_size's auto / iso values, one per vertex,
 * size: nv): the curvature cap and (spacing: 1) the feature spacing, at
 * least size_min h, graded. The refinement to the local size
 * (surface_refine.c) targets it without the spacing. */
struct glpgp_surface_constraints;
glpgp_status glpgp_surface_size_local(const glpgp_mesh *m, const glpgp_options *o,
                                      const struct glpgp_surface_constraints *con, double h, int spacing,
                                      double *size);

/* s_i <- min(s_i, min_j s_j + g |x_i - x_j|) along a surface's edges
 * (Dijkstra; surface_size.c): with g = 1 and s 0 at the sources, the
 * distance to them along the edges. */
glpgp_status glpgp_surface_grade(const glpgp_mesh *m, double g, double *s);

/* U_a of corner a of triangle t in the frame the matching compares in: the
 * plane's (u itself) or, on a surface, t's (coupled.c). */
void glpgp_coupled_corner_u(const glpgp_mesh *m, const double *u, int t, int a, double *out);

/* z <- z exp(i a) (2 doubles; surface_transfer.c) */
void glpgp_turn(double *z, double a);
/* The angle in triangle T's plane of surface s (its frame E1, E2) of the 3D vector d (surface_transfer.c). */
double glpgp_plane_angle(const glpgp_surface *s, int T, const double *d);

/* A surface refined to its local size (surface_refine.c): every edge longer
 * than h(x) / GLPGP_SURFACE_EDGES bisected (glpgp_mesh_refine_surface_sized),
 * h(x) glpgp_surface_size_local's curvature cap on m (auto / iso; h for the other size
 * fields: glpgp_mesh_refine_surface to h / N), within max_triangles; *out
 * NULL when no edge needed it. Up to GLPGP_SURFACE_REFINE_PASSES passes,
 * the size recomputed on each refined mesh; info->passes those that split,
 * info->ratio the largest edge / (h(x) / N) on the result with h(x)
 * recomputed on it (glpgp_surface_edge_ratio). */
glpgp_status glpgp_surface_refine_local(const glpgp_mesh *m, const glpgp_options *o, double h, double max_triangles,
                                        glpgp_mesh **out, glpgp_surface_refine_info *info);
/* The largest edge / (h(x) / GLPGP_SURFACE_EDGES) over m's edges (*ratio,
 * <= 1: N edges per local period everywhere), h(x) the smaller local size
 * of the edge's ends computed on m itself, and its smallest (*min_size);
 * either may be NULL. */
glpgp_status glpgp_surface_edge_ratio(const glpgp_mesh *m, const glpgp_options *o, double h, double *ratio,
                                      double *min_size);

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

/* min, 10th percentile (p10 may be NULL) and median of |z| over nv complex
 * values (scratch: nv doubles), selected on |z|^2 (no hypot per value; the
 * same order up to rounding), one square root per result */
double glpgp_zabs_median(const double *z, int nv, double *scratch, double *min, double *p10);

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

/* The cross field's Newton levels (crossfield.c): eps from cross_eps0 x the
 * diagonal down to cross_eps_min mean edges, each to cross_rtol, from the
 * state's x on backend b (set up with the cross system, its QUAD assembled);
 * a level starting at a critical point up to rounding is skipped. Fills
 * c's levels and counts. Shared by the planar and the surface cross field. */
struct glpgp_cross_result;
/* The INFO line of a finished cross field (crossfield.c). */
void glpgp_cross_log_done(const struct glpgp_cross_result *c);
glpgp_status glpgp_cross_levels(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                glpgp_newton_state *ns, struct glpgp_cross_result *c);
/* The five vectors of a cross-field solve (x, g, d, xt, work; n2 entries
 * each) created on b; on failure the ones made are destroyed (crossfield.c). */
glpgp_status glpgp_cross_vecs_create(glpgp_backend *b, size_t n2, glpgp_vec **x, glpgp_vec **g, glpgp_vec **d,
                                     glpgp_vec **xt, glpgp_vec **work);
void glpgp_cross_vecs_destroy(glpgp_backend *b, glpgp_vec **x, glpgp_vec **g, glpgp_vec **d, glpgp_vec **xt,
                              glpgp_vec **work);
/* The end of a cross-field solve from the state ns (its x holds the initial
 * guess, on the device): the GL continuation when levels, c->w read back,
 * analysed, timed from t0 and logged (crossfield.c). */
glpgp_status glpgp_cross_finish(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                glpgp_newton_state *ns, int levels, double t0, struct glpgp_cross_result *c);
/* |w_i| <- 1 for the nv complex values of w (phase kept; 1 where |w_i| vanishes). */
void glpgp_cross_unit(double *w, int nv);

/* ---- one oscillator's solve (continuation.c), shared with the surface
 * pipeline (surface_solve.c) ---- */
/* The driver's vectors and state of one oscillator solve on backend b. */
typedef struct osc_work {
    glpgp_backend *b;
    const glpgp_options *o;
    glpgp_vec *x, *g, *d, *xt, *work;
    double *host, *scratch;
    glpgp_amg *amg; /* multigrid preconditioner of the current oscillator (NULL: Jacobi) */
    int *stop;      /* concurrent oscillators: 0, or 1 + the oscillator that failed first
                       (the other's Newton levels then end at their next step) */
    /* optional (NULL: none): the initial guess of an oscillator without Dirichlet
     * nodes, for naive PGP and the GL init "naive" (the naive solve would give 0):
     * x <- it, with QUAD assembled and w->amg created (a surface: the quadratic
     * form's smallest eigenvector, surface_solve.c); ctx: its data */
    glpgp_status (*init_free)(struct osc_work *w, int k, glpgp_osc_result *r);
    void *init_ctx;
} osc_work;
/* w <- the driver's vectors on backend b (set up): x, g, d, xt, work of n
 * unknowns, host (n doubles) and scratch (ns doubles); the rest zero. Free:
 * glpgp_osc_work_free (also after a failure part-way). */
glpgp_status glpgp_osc_work_create(osc_work *w, glpgp_backend *b, const glpgp_options *o, size_t n, size_t ns);
void glpgp_osc_work_free(osc_work *w);
/* One oscillator (k = 0, 1) on mesh m, or the coupled pair (k = 3) on a
 * coupled system's virtual mesh m with its Dirichlet set dir_given: the
 * field hostw, sizes (NULL: uniform h), naive PGP or the GL continuation over
 * eps[0 .. nlevels) into r (with dir_given not summarised: the caller
 * splits it per vertex first). */
glpgp_status glpgp_solve_oscillator(const glpgp_mesh *m, osc_work *w, int k, const double *hostw,
                                    const double *size, glpgp_osc_result *r, double h, const double *eps,
                                    int nlevels, const unsigned char *dir_given);

/* The coupled pair (z_u, z_v) of mesh m with representatives r->field
 * (continuation.c): one GL solve on the coupled system, split per vertex into
 * r->osc[0], r->osc[1] (statistics in osc[0]), frame windings, r->coupled.
 * dn_given (2 nv, NULL: the planar boundary rule) the Dirichlet nodes;
 * init_free, init_ctx: osc_work's (NULL: none). */
glpgp_status glpgp_solve_coupled(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o, glpgp_result *r,
                                 const double *size, double h, const double *eps, int nlev, const unsigned char *dn_given,
                                 glpgp_status (*init_free)(osc_work *w, int k, glpgp_osc_result *r), void *init_ctx);

/* Inverse iteration towards the smallest eigenvector of NEWTON (assembled
 * without penalty and Dirichlet rows: QUAD) against the lumped mass
 * (surface_cross.c): from x, x <- NEWTON^-1 (M x) scaled to a mean |z|^2 of 1,
 * each solve to 1e-4 (the multigrid *amg, updated with x as its frames; set
 * to NULL when it fails), until the Rayleigh quotient x.QUAD x / x.M x
 * changes by less than 1e-3 or after maxsteps steps. mass: n (pairs of
 * unknowns); host: 2 n scratch. *cg += the CG iterations; returns the steps
 * in *steps. */
glpgp_status glpgp_inverse_iteration(glpgp_backend *b, const glpgp_options *o, glpgp_amg **amg, glpgp_vec *x,
                                     glpgp_vec *y, glpgp_vec *rhs, glpgp_vec *work, const double *mass, int n,
                                     double *host, int maxsteps, long *cg, int *steps);

/* One INFO line about a non-uniform size field (solver/sizefield.c). */
void glpgp_size_log(const glpgp_mesh *m, const double *size, double h);

#endif
