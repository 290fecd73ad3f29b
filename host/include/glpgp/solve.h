/* glpgp/solve.h: the GL-PGP pipeline on one mesh, backend-agnostic (it
 * drives a glpgp_backend through glpgp/backend.h):
 *   guiding field (solver/field.c), Dirichlet sets (solver/dirichlet.c),
 *   naive PGP or the Ginzburg-Landau Newton continuation in eps for the two
 *   oscillators z_u, z_v (solver/continuation.c, solver/newton.c, with the
 *   one PCG of solver/cg.c), singularities and statistics (glpgp/result.h).
 * Every number the drivers use is a member of glpgp_options, documented and
 * defaulted by glpgp_options_default. Progress and warnings go through the
 * log callback of glpgp/status.h. Layer: solver. */
#ifndef GLPGP_SOLVE_H
#define GLPGP_SOLVE_H

#include "glpgp/backend.h"
#include "glpgp/kinds.h" /* GLPGP_ELEM_* and GLPGP_HESS_* */
#include "glpgp/optdesc.h"
#include "glpgp/result.h"
#include "glpgp/surface.h" /* glpgp_surface_denoise_info */

#ifdef __cplusplus
extern "C" {
#endif

enum glpgp_method { GLPGP_METHOD_GL = 0, GLPGP_METHOD_PGP = 1 };
enum glpgp_field {
    GLPGP_FIELD_BOUNDARY = 0, GLPGP_FIELD_RADIAL = 1, GLPGP_FIELD_FILE = 2,
    GLPGP_FIELD_CROSS = 3 /* U from the Ginzburg-Landau cross field (glpgp/cross.h) */
};
/* --field cross with singularities: the two oscillators coupled across the
 * cross field's cuts (glpgp/cross.h, solver/coupled.c), or solved apart. */
enum glpgp_cross_coupling {
    GLPGP_COUPLING_AUTO = 0, /* coupled when the representatives have cuts and the backend can */
    GLPGP_COUPLING_OFF = 1,  /* never: u and v solved apart (they see the cuts) */
    GLPGP_COUPLING_ON = 2    /* coupled when there are cuts; a backend that cannot is an error */
};
/* --field cross on a surface refined for its size (glpgp_solve_prepare):
 * the mesh the cross field is solved on. */
enum glpgp_cross_mesh {
    GLPGP_CROSS_MESH_INPUT = 0,  /* the input, before the refinement; carried onto the refined mesh
                                    (glpgp_surface_cross_transfer) */
    GLPGP_CROSS_MESH_REFINED = 1, /* the refined mesh (the solve's own) */
    GLPGP_CROSS_MESH_POLISH = 2   /* INPUT, then the refined mesh's last eps level from it */
};
/* --field cross: the local size from the cross field's conformal factor phi
 * (glpgp_cross_conformal_size), s = h clamp(e^{phi - phi_q}, 1/c, 1), phi_q the
 * q-quantile of phi over the vertices; the smaller of it and the size field's. */
enum glpgp_cross_size {
    GLPGP_CROSS_SIZE_OFF = 0, /* the size field's alone */
    GLPGP_CROSS_SIZE_ON = 1,  /* q = 1 (largest size h), no ratio bound: fully conformal */
    GLPGP_CROSS_SIZE_AUTO = 2 /* q = cross_size_quantile, c = cross_size_ratio (docs/numerics.md) */
};

/* glpgp_options.denoise: where a surface shows a scan's noise (interior
 * edges above the feature angle that are not creases), smooth it away
 * before the solve (AUTO), or solve the input as it is (OFF). */
enum { GLPGP_DENOISE_OFF = 0, GLPGP_DENOISE_AUTO = 1 };
enum glpgp_init { GLPGP_INIT_NAIVE = 0, GLPGP_INIT_ONE = 1 };
/* How the two oscillators of a solve share the machine (glpgp_options.oscillators). */
enum glpgp_oscillators {
    GLPGP_OSC_AUTO = 0,       /* concurrent when the backend can be cloned, the host has two
                                 or more cores and the memory for a second copy */
    GLPGP_OSC_SEQUENTIAL = 1, /* u, then v, on the one backend */
    GLPGP_OSC_CONCURRENT = 2  /* v on a clone of the backend in a second host thread while u
                                 runs; a backend or host that cannot: sequential, one warning */
};

/* Vertex numbering of the solve (glpgp_options.vertex_order). */
enum glpgp_vertex_order { GLPGP_ORDER_RCM = 0, GLPGP_ORDER_INPUT = 1 };
/* How a Newton step is made safe: a trust region around the exact-Hessian
 * model (Steihaug-Toint CG), or the line search of the modified Newton. */
enum glpgp_globalization { GLPGP_GLOBAL_TRUST_REGION = 0, GLPGP_GLOBAL_LINE_SEARCH = 1 };
/* Preconditioner of the Newton (and naive PGP, guiding field) systems. */
enum glpgp_precond {
    GLPGP_PRECOND_JACOBI = 0, /* 2x2-block Jacobi, CG (solver/cg.c) */
    GLPGP_PRECOND_AMG = 1     /* aggregation multigrid, flexible CG (solver/amg.c) */
};
/* Local target size h(x) (solver/sizefield.c, docs/numerics.md "Local size"). */
enum glpgp_size_mode {
    GLPGP_SIZE_NONE = 0, /* h everywhere (today's uniform size) */
    GLPGP_SIZE_AUTO = 1, /* local feature size from the boundary, per oscillator along its W */
    GLPGP_SIZE_ISO = 2,  /* the same, isotropic: one size for both oscillators */
    GLPGP_SIZE_FILE = 3, /* one "h" or "h_u h_v" line per vertex from size_file */
    GLPGP_SIZE_FUNC = 4  /* AUTO, further limited by a user function of position
                            (size_fn: e.g. a grey-level image, glpgp/image.h) */
};
/* A user size field: the local size at (x, y) as a fraction of h, in (0, 1]
 * (values outside are clamped to [size_min, 1]); ctx is o->size_ctx. */
typedef double (*glpgp_size_fn)(void *ctx, double x, double y);
/* Multigrid cycle on the coarse levels. */
enum glpgp_amg_cycle {
    GLPGP_AMG_KCYCLE = 0, /* two flexible-CG steps per coarse level (K-cycle) */
    GLPGP_AMG_VCYCLE = 1  /* one plain visit per coarse level (V-cycle) */
};

/* Every parameter of a solve (defaults in brackets). */
typedef struct glpgp_options {
    /* what is solved */
    double size;          /* target quad size h; <= 0: glpgp_default_size() [0] */
    int method;           /* GLPGP_METHOD_* [GL] */
    int energy;           /* GLPGP_ELEM_P1 or GLPGP_ELEM_TRANSPORT [P1] */
    int hess;             /* GLPGP_HESS_MIXED, _PROJECTED or _PAPER [MIXED] */
    int field;            /* GLPGP_FIELD_* [BOUNDARY] */
    const char *field_file; /* for GLPGP_FIELD_FILE: one "ux uy" line per vertex [NULL] */
    const double *field_values; /* for GLPGP_FIELD_FILE: the field in memory instead of the file, 2 nv
                             values (ux, uy per vertex of the solved mesh, normalised here; field_file
                             then only names it in messages and the statistics) [NULL] */
    int has_center;       /* radial field center given (else: area centroid) [0] */
    double center[2];
    int init;             /* initial guess of GL: GLPGP_INIT_NAIVE or ONE [NAIVE] */
    int vertex_order;     /* GLPGP_ORDER_RCM: glpgp_solve renumbers the vertices for
                             memory locality (reverse Cuthill-McKee; an input whose edges
                             span at most 3 sqrt(nv) indices on average is local already
                             and keeps its order) and returns the
                             result in m's order; GLPGP_ORDER_INPUT: m's numbering [RCM] */
    int oscillators;      /* GLPGP_OSC_*: u and v one after the other or at the same time
                             (independent solves: the same result bit for bit) [AUTO] */
    int phase_sync;       /* 1: the drivers wait for the device at the end of every timed
                             phase (glpgp/timers.h), so that each phase's time includes its
                             device work (one more host round trip per phase); 0: a phase
                             books only what the host did and waited for during it [0] */

    /* eps continuation */
    double eps0;          /* first eps as a multiple of h [0.5] */
    double eps_ratio;     /* eps_{k+1} = ratio * eps_k [0.5] */
    double eps_min;       /* last eps as a multiple of the mean edge length [2.5] */
    double eps_merge;     /* a last level within this factor of the previous one is
                             dropped (the previous one is lowered to eps_min) [1.25] */
    double collapse_zabs; /* a level ending with median |z| below this is restarted
                             once from z = 1 [0.5] */

    /* cross field (--field cross, glpgp/cross.h): its own eps schedule, same
       eps_ratio and eps_merge */
    double cross_eps0;    /* first eps as a multiple of the bounding-box diagonal [0.05] */
    double cross_eps_min; /* last eps as a multiple of the mean edge length [2.5] */
    double cross_rtol;    /* every cross level stops when |g| <= this |g_0| (the singularities
                             are placed long before; later steps are slow vortex drift) [1e-3] */
    double cross_ftol;    /* ... or, from its GLPGP_STALL_STEPS-th Newton step on, when E + P
                             fell by at most this fraction of itself over the last 3 (the drift
                             stalls: a sphere's 8 singularities settle at 1e-6 per step)
                             [1e-5; 0: off] */
    int cross_coupling;   /* GLPGP_COUPLING_* [AUTO] */
    int cross_mesh;       /* GLPGP_CROSS_MESH_*: a refined surface's cross field solved on its
                             input and carried over (then polished), or on the refined mesh
                             [POLISH] */
    double cross_align;   /* a surface's cross field: weight lambda of the principal-curvature
                             term -lambda int Re(conj(w) q), q the cross of the principal
                             directions times ((k1 - k2) / 2)^2 (glpgp_surface_align_source;
                             0: the smoothest field only) [5] */
    int cross_size;       /* GLPGP_CROSS_SIZE_*: local size from the cross field
                             (glpgp_cross_conformal_size), the smaller of it and the size
                             field's, for both oscillators [AUTO] */
    double cross_size_quantile; /* AUTO: phi's quantile that gets size h, in (0, 1] [0.9] */
    double cross_size_ratio;    /* AUTO: the size stays >= h / this, >= 1 [1.4] */

    /* Newton */
    double newton_rtol;   /* stop the last level when |g| <= rtol |g_0| [1e-6] */
    double intermediate_rtol; /* levels before the last stop at max(newton_rtol, this) [1e-3] */
    int newton_max;       /* Newton iterations cap per eps level [50] */
    double newton_ftol;   /* a level also stops, from its GLPGP_STALL_STEPS-th step on, when
                             E + P fell by at most this of itself over the last 3 steps
                             (0: off) [1e-8] */
    double exact_switch;  /* `mixed` tries the exact Hessian once |g| <= this |g_0| after a
                             full step without fallback [0.05] */
    int exact_cooldown;   /* steps `mixed` waits after a failed exact attempt [5] */
    double armijo;        /* line search: accept F(x + a d) <= F + armijo a g.d [1e-4] */
    int max_backtracks;   /* line search halvings before the step is given up [40] */
    double forcing;       /* inexact Newton: CG tolerance eta = forcing |g| / |g_0| ... [0.1] */
    double forcing_max;   /* ... clamped to [cg_rtol, forcing_max] [1e-2] */
    int globalization;    /* GLPGP_GLOBAL_* [TRUST_REGION] */
    /* trust region (radius in the norm ||d||_M = sqrt(d.M d) of the region's
     * preconditioner: block Jacobi, or the multigrid of tr_precond):
     * rho = (actual decrease of E + P) / (decrease predicted by the model) */
    double tr_accept;     /* a trial point is taken when rho >= this, [0, tr_poor) [1e-4] */
    double tr_poor;       /* rho below this after a full step shrinks the radius ... (0, tr_good) [0.25] */
    double tr_shrink;     /* ... to at most this times the step length; also the largest
                             backtracking factor, (0, 1) [0.5] */
    double tr_shrink_min; /* ... and at least this times it; also the smallest backtracking
                             factor, (0, tr_shrink] [0.1] */
    double tr_good;       /* rho above this with a step on the boundary ... (tr_poor, 1) [0.75] */
    double tr_grow;       /* ... multiplies the radius by this, > 1 [2] */
    int tr_resolve;       /* a step cut by the region (boundary or negative curvature) whose
                             full step fails (rho < tr_accept) or is poor (rho <
                             tr_resolve_rho) is solved again, up to this many times, in the
                             region shrunk by tr_resolve_shrink, on the same Hessian (no new
                             assembly); then backtracking along d; >= 0, 0: off [3] */
    double tr_resolve_shrink; /* ... (0, 1) [0.7] */
    double tr_resolve_rho;    /* ... [tr_accept, tr_poor] [0.1] */
    int tr_precond;       /* trust region, with precond AMG: the Steihaug-Toint CG's
                             preconditioner and norm, GLPGP_PRECOND_JACOBI (block Jacobi)
                             or _AMG (the symmetric multigrid cycle of glpgp_amg_apply_spd on
                             the projected Hessian) [AMG] */
    int tr_lookahead;     /* 1: where the Steihaug path leaves the region, CG goes on to the
                             inexact Newton step and tries it first (kept when its rho >=
                             tr_poor; the region then grows to its length), 0: off [0] */
    double retract_zabs;  /* trial points follow z (1 + Re w) e^{i Im w}, w = d/z, where
                             |z| >= this, z + d below half of it; 0: z + d everywhere;
                             [0, 2] [0.8] */

    /* CG */
    double cg_rtol;       /* CG: |r| <= rtol |b| [1e-8] */
    int cg_max;           /* CG iteration cap [20000] */
    int cg_check;         /* read the residual back every k iterations [10] */

    /* preconditioner (glpgp/solve.h: glpgp_amg_*) */
    int precond;          /* GLPGP_PRECOND_JACOBI or _AMG [AMG] */
    int amg_coarse;       /* coarsening stops at <= this many nodes (2 unknowns each),
                             solved by a dense inverse; 2 .. 1024 [48] */
    int amg_max_levels;   /* levels including the fine one, 2 .. GLPGP_AMG_MAX_LEVELS [20] */
    int amg_coarse_passes; /* pairwise-matching passes that aggregate each level >= 1: 2
                             (aggregates of ~4 nodes) or 3 (~8: fewer levels, half the
                             launches per cycle, 5-15% more iterations; level 0 keeps 2) [2] */
    int amg_cycle;        /* GLPGP_AMG_KCYCLE or _VCYCLE [KCYCLE] */
    int amg_kcycle_min;   /* with KCYCLE: levels with fewer nodes than this get a plain
                             visit (V) instead, fewer small operations per cycle for a
                             device with launch latency; >= 0, or -1: by the backend
                             (glpgp_amg_kcycle_min) [-1] */
    int amg_pre;          /* l1-Jacobi sweeps before the coarse correction, 0 .. 8 [1] */
    int amg_post;         /* l1-Jacobi sweeps after the coarse correction, 1 .. 8 [1] */
    double amg_weight;    /* l1-Jacobi weight, in (0, 2) (convergent for any SPD matrix) [1.5] */
    int amg_check;        /* flexible CG reads the residual back every k iterations [1] */
    int amg_maxit;        /* flexible-CG cap (the smaller of this and cg_max) [1000] */

    /* local size h(x) (glpgp_size_compute); h above is the largest size */
    int size_field;       /* GLPGP_SIZE_* [AUTO: measured better than NONE, README "Local size"] */
    const char *size_file; /* for GLPGP_SIZE_FILE [NULL]; GLPGP_SIZE_FUNC: names the
                             source of size_fn in messages (e.g. the image) */
    glpgp_size_fn size_fn; /* for GLPGP_SIZE_FUNC [NULL] */
    void *size_ctx;        /* its context [NULL] */
    double size_grading;  /* g: h_i <= h_j + g |x_i - x_j| on every mesh edge, > 0 [0.5] */
    double size_across;   /* periods (quads) across a feature (wall, strip, slot, hole), >= 1 [2] */
    double size_min;      /* smallest local size as a fraction of h, in (0, 1] [0.05]: cusps and
                             wedge tips (feature size -> 0) stop there; the repair meshes what
                             is thinner */
    double size_chord_area; /* boundary chords: auto / iso / function sizes are capped at
                             c R (R: the boundary's radius of curvature) near curved parts
                             when the chords' predicted area error (lost on convex arcs net
                             of gained on concave ones, netting only arcs of >= 4 pi chords
                             per turn) exceeds this fraction F of the domain's area, or a
                             side's part that does not net F, or a side at 1.4x its
                             prediction 2 F net; that side's c the largest bringing it
                             within F; 0: off [0.005] */
    double size_chord_depth; /* ... and where a chord's sagitta would exceed this fraction of
                             h, the size is capped so that it does not; 0: off [0.125] */
    double size_resolution; /* a triangle's longest edge should be <= its local h / this:
                             glpgp_size_refine refines to it, glpgp_solve warns below it
                             (and fails below GLPGP_SIZE_MIN_EDGES), >= 2 [4] */

    /* default h (glpgp_default_size) */
    double size_diag_div; /* h = bounding-box diagonal / this ... [20] */
    double size_min_edges;/* ... raised to this many mean edges [10] */

    /* cancellation: polled before every Newton step by each thread running
     * the solve (both oscillators' threads, the cross field's); a non-zero
     * return ends the solve with GLPGP_ERR_CANCELLED and no result. NULL:
     * never [NULL]. The Python binding polls Ctrl-C (its signals) here. */
    int (*cancel)(void *ctx);
    void *cancel_ctx;     /* its argument [NULL] */
    /* surfaces (glpgp/surfsolve.h) */
    double feature_angle; /* an interior edge whose triangles' normals differ by more than this
                             many degrees is a sharp feature: the cross field and the
                             oscillators align with it as with the boundary; [0, 180]; 180:
                             none [GLPGP_FEATURE_ANGLE_DEFAULT = 35] */
    double size_curl;     /* a surface's local size scaled by e^(-F phi), phi making the guiding
                             frame curl-free (glpgp_surface_size_curl): fewer dislocations where
                             the surface curves (size_field AUTO or ISO only); 0: off [1] */
    double rim_scale;     /* the boundary's crosses read over rim_scale h on either side of a
                             vertex (glpgp_surface_constraints_rims; at least
                             GLPGP_RIM_EDGES of the rim's edges); 0: its own edges [0] */
    int denoise;          /* GLPGP_DENOISE_*: a scan's noise smoothed out of the surface before
                             the solve (glpgp_solve_prepare, glpgp_surface_denoise) [AUTO] */
} glpgp_options;

/* Fill the documented defaults. */
void glpgp_options_default(glpgp_options *o);

/* The user-settable members of glpgp_options, one descriptor each
 * (glpgp/optdesc.h; solver/option_table.c): the options of `glpgp solve`'s
 * groups "Parametrization" and "Continuation and solvers", then
 * "input-order" (group NULL: the command places it). --field, --center and
 * --size-field are TEXT options: a FILE or IMAGE name is kept, not copied
 * (it must outlive the solve); an IMAGE size field needs size_fn set by the
 * caller. The CLI's parser and the Python keyword arguments read it. */
const glpgp_optdesc *glpgp_solve_option_table(void);

/* Check the values (ranges as documented; GLPGP_ERR_ARG naming the member). */
glpgp_status glpgp_options_check(const glpgp_options *o);

/* The size limits for a mesh: h (o->size, or the default size) must be at
 * least GLPGP_SIZE_MIN_EDGES mean edge lengths (a period needs vertices to
 * exist on; P1 wants about 10) and at most GLPGP_SIZE_MAX_DIAG times the
 * bounding-box diagonal (beyond, there is no grid line to compute).
 * GLPGP_ERR_ARG with a message naming the ratio otherwise. */
#define GLPGP_SIZE_MIN_EDGES 2.0
/* A surface's edges longer than h / GLPGP_SURFACE_EDGES are bisected
 * (glpgp_solve_prepare, glpgp_mesh_refine_surface; at about 4 mean edges
 * per period the oscillators collapse towards z = 0). Longest edge h / 6
 * leaves a mean edge of about h / 9.4 (the former rule, mean edge <= h / 8
 * by uniform rounds, left h / 8 to h / 16): bench/results/surface_refine.md. */
#define GLPGP_SURFACE_EDGES 6.0
/* --denoise auto moves a surface's vertices by at most h / this (the quads'
 * distance to the input: at most their distance to the smoothed surface
 * plus h / 10; the summary measures it). Measured against h / 4 on the
 * 20 x 20 box with a jitter of 0.3 edges at 300 faces (h = 2.8 edges): no
 * better (bench/results/surface_features.md). */
#define GLPGP_DENOISE_MAX_MOVE 10.0
#define GLPGP_SIZE_MAX_DIAG 100.0
/* `glpgp solve` with refinement: a default size above diameter / this (the
 * raise to 10 mean edges on a coarse input) is replaced by diameter / 20 and
 * the mesh refined for it */
#define GLPGP_SIZE_DEFAULT_MIN_QUADS 5.0
/* --size-field auto / iso: boundary loops shorter than this many h (holes of
 * radius below 0.72 h) let the rays of the rest of the boundary pass: they
 * make no walls (solver/sizefield.c, step 1) */
#define GLPGP_SIZE_SMALL_LOOP 4.5
/* triangles with a corner below this many degrees are slivers (a warning
 * when they are 1% of the input or more) */
#define GLPGP_SLIVER_DEG 5.0
glpgp_status glpgp_options_check_mesh(const glpgp_options *o, const glpgp_mesh *m);

/* ---- local size (solver/sizefield.c) ----
 * Per-vertex target sizes of the two oscillators: size[0 .. nv) for u,
 * size[nv .. 2 nv) for v. h is the user's (largest) size. */

/* The size field of option o->size_field for mesh m: NONE: h; AUTO: the
 * local feature size measured along each oscillator's field (u: the guiding
 * field U, 2*nv; v: U rotated by +90 degrees); AUTO with u NULL, and ISO: the
 * isotropic size (a lower bound of AUTO's); FILE: read from o->size_file;
 * FUNC: AUTO's seeds further limited to h o->size_fn(x_i) (clamped to
 * [size_min h, h]) at every vertex, then graded like AUTO -- so the user's
 * field can only make quads smaller than AUTO's, and thin features keep
 * their periods across.
 * AUTO, ISO and FUNC are limited to what m resolves: a value below
 * o->size_resolution x the longest mesh edge at its vertex is raised to that
 * (at most h), so the solve never asks for periods the mesh cannot carry
 * (glpgp_size_refine refines the input first where it should).
 * *uniform (may be NULL) <- 1 when every value equals h exactly (the solve
 * then uses the uniform element arithmetic, bit for bit). */
glpgp_status glpgp_size_compute(const glpgp_mesh *m, const glpgp_options *o, double h, const double *u,
                                double *size, int *uniform);

/* Local resolution of a mesh for a size field: per triangle T,
 * q_T = (smallest size at T's corners, both oscillators) / (longest edge). */
typedef struct glpgp_size_res {
    double worst;   /* min q_T */
    int tri;        /* the triangle where it is reached */
    double x, y;    /* its centroid */
    double lmax, h; /* its longest edge and size */
    int coarse;     /* triangles with q_T < R */
} glpgp_size_res;
glpgp_status glpgp_size_resolution(const glpgp_mesh *m, const double *size, double R, glpgp_size_res *res);

/* The local resolution check of glpgp_solve (max edge against the local
 * size, not the mean edge), with the isotropic size (AUTO, limited to what
 * the mesh resolves: a warning line when the limit raised any value), the
 * file's, or h (NONE): GLPGP_ERR_MESH naming the place when a triangle has
 * q_T < GLPGP_SIZE_MIN_EDGES (NONE: a warning only, today's pipeline), one
 * warning line when some have q_T < o->size_resolution. */
glpgp_status glpgp_size_check_mesh(const glpgp_mesh *m, const glpgp_options *o, double h);

/* Refinement of the triangles too coarse for the local size (q_T <
 * o->size_resolution, isotropic size), by conforming longest-edge bisection
 * in rounds, the sizes recomputed on each new mesh, until none is left.
 * *out <- the refined mesh, or NULL when nothing needed refining (and
 * always for GLPGP_SIZE_NONE, today's pipeline on the input as it is, and
 * GLPGP_SIZE_FILE, whose values belong to m's vertices).
 * GLPGP_ERR_LIMIT (naming the place) beyond GLPGP_REFINE_MAX_ROUNDS rounds
 * or GLPGP_REFINE_MAX_VERTICES vertices. info may be NULL. */
#define GLPGP_REFINE_MAX_ROUNDS 64
#define GLPGP_REFINE_MAX_VERTICES 8000000
typedef struct glpgp_refine_info {
    int rounds;           /* rounds of the planar refinement (0 on a surface) */
    long split_edges;     /* edges bisected */
    int nv0, nt0, nv, nt; /* before and after */
    double target_edge;   /* a surface: the longest edge asked (h / GLPGP_SURFACE_EDGES; refined to the
                             local size: the smallest asked, min h(x) / GLPGP_SURFACE_EDGES); 0 in the plane */
    int local;            /* a surface refined to its local size h(x) (size field auto / iso) */
    double edge_ratio;    /* a surface: the largest edge / (h(x) / GLPGP_SURFACE_EDGES) on the refined
                             mesh, h(x) recomputed there as the solve does (<= 1: reached) */
} glpgp_refine_info;
glpgp_status glpgp_size_refine(const glpgp_mesh *m, const glpgp_options *o, double h, glpgp_mesh **out,
                               glpgp_refine_info *info);

/* What a front end does between reading a domain m and glpgp_solve, the
 * same for the CLI's `glpgp solve` and Python's glpgp.solve (name: the
 * input's name in messages; refine_ok: 0 for --no-refine): one warning when
 * 1% or more of the triangles are slivers; with refinement (refine_ok, a
 * size field auto / iso / function, no field file) a default size above
 * diameter / GLPGP_SIZE_DEFAULT_MIN_QUADS becomes diameter / size_diag_div
 * (o->size set); the size checked against the mesh
 * (glpgp_options_check_mesh; below 2 mean edges with refinement: against
 * max_triangles for the refined mesh, > 0, else no limit); a field file
 * read once; the triangles too coarse for the local size refined
 * (glpgp_size_refine; o->size then set to h); a surface's edges longer
 * than h / GLPGP_SURFACE_EDGES bisected (glpgp_mesh_refine_surface, within
 * max_triangles), after its scan noise is smoothed away (o->denoise,
 * glpgp_surface_denoise: vertices moved by at most h / 10; info->denoise).
 * *refined <- the refined (or denoised) mesh
 * to solve instead of m (free it with glpgp_mesh_destroy), or NULL: solve m.
 * On failure info->usage tells whether it is about the option values (the
 * CLI's usage error, "--size: MESSAGE") rather than the input. */
typedef struct glpgp_prepare_info {
    glpgp_refine_info refined; /* split_edges 0: not refined */
    int usage;                 /* the failure concerns the size or another option value */
    double seconds_refine;     /* the refinement's wall seconds (0: none) */
    glpgp_surface_denoise_info denoise; /* a surface's noise smoothed (rounds 0: none) */
    double denoise_h;          /* the size h the moves are measured against */
} glpgp_prepare_info;
glpgp_status glpgp_solve_prepare(const glpgp_mesh *m, glpgp_options *o, const char *name, double max_triangles,
                                 int refine_ok, glpgp_mesh **refined, glpgp_prepare_info *info);

/* Run the whole pipeline on mesh m with backend b (already created; setup is
 * done here). On success *out holds the result (free with
 * glpgp_result_destroy), per vertex in m's order. With o->vertex_order =
 * GLPGP_ORDER_RCM (the default) the solve itself runs on m renumbered in
 * reverse Cuthill-McKee order (glpgp_mesh_rcm_order), except on a part of a
 * distributed mesh (m->part), with per-vertex input files (field or size
 * FILE, whose lines follow m's numbering) and with the cross field (whose
 * coupled solve's cuts and frames follow the numbering): the same result up to rounding,
 * 1.2-1.5x less CPU on randomly numbered meshes (docs/numerics.md). Progress: glpgp_log at GLPGP_LOG_INFO; a level that
 * stops at the Newton cap is flagged (level[].capped, capped_levels) and
 * logged as a warning. */
glpgp_status glpgp_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                         glpgp_result **out);

/* Default h for a mesh: diagonal of its bounding box / size_diag_div, raised
 * to size_min_edges mean edge lengths when the mesh is too coarse for that
 * (o NULL: the defaults). */
double glpgp_default_size(const glpgp_mesh *m, const glpgp_options *o);

/* The eps schedule for mesh m and size h: eps0 h, times eps_ratio, down to
 * eps_min mean edges (a last level within eps_merge of the previous one is
 * merged). Returns the number of levels (<= GLPGP_MAX_LEVELS). */
int glpgp_eps_schedule(const glpgp_mesh *m, const glpgp_options *o, double h,
                       double eps[GLPGP_MAX_LEVELS]);

/* The lower-level pieces (the guiding field's steps, the Dirichlet set, one
 * Newton step, CG, the multigrid) are internal: glpgp/internal/newton.h. */

#ifdef __cplusplus
}
#endif

#endif
