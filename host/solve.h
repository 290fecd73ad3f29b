/* solve.h: the GL-PGP pipeline on one mesh: guiding field, Dirichlet sets,
 * naive PGP or Ginzburg-Landau Newton continuation for the two oscillators
 * z_u, z_v, singularities and statistics. Backend-agnostic: it drives a
 * glpgp_backend (reference or OpenCL) through backend.h. */
#ifndef GLPGP_SOLVE_H
#define GLPGP_SOLVE_H

#include "backend.h"
#include "element.h" /* GLPGP_ELEM_* and GLPGP_HESS_* constants */

enum glpgp_method { GLPGP_METHOD_GL = 0, GLPGP_METHOD_PGP = 1 };
enum glpgp_field { GLPGP_FIELD_BOUNDARY = 0, GLPGP_FIELD_RADIAL = 1, GLPGP_FIELD_FILE = 2 };
enum glpgp_init { GLPGP_INIT_NAIVE = 0, GLPGP_INIT_ONE = 1 };

#define GLPGP_MAX_LEVELS 32

typedef struct glpgp_options {
    double size;          /* target quad size h; <= 0: glpgp_default_size() */
    int method;           /* GLPGP_METHOD_* (default GL) */
    int energy;           /* GLPGP_ELEM_P1 (default) or GLPGP_ELEM_TRANSPORT */
    int hess;             /* GLPGP_HESS_MIXED (default), _PROJECTED or _PAPER */
    int field;            /* GLPGP_FIELD_* (default BOUNDARY) */
    const char *field_file; /* for GLPGP_FIELD_FILE: one "ux uy" line per vertex */
    int has_center;       /* radial field centre given (else: area centroid) */
    double center[2];
    int init;             /* initial guess of GL: GLPGP_INIT_NAIVE (default) or ONE */
    double eps0;          /* first eps as a multiple of h (default 0.5) */
    double eps_ratio;     /* eps_{k+1} = ratio * eps_k (default 0.5) */
    double eps_min;       /* last eps as a multiple of the mean edge length (default 2.5) */
    double newton_rtol;   /* stop a level when |g| <= rtol |g_0| (default 1e-6) */
    int newton_max;       /* Newton iterations cap per eps level (default 50) */
    double cg_rtol;       /* CG: |r| <= rtol |b| (default 1e-8) */
    int cg_max;           /* CG iteration cap (default 20000) */
    int cg_check;         /* read the residual back every k iterations (default 10) */
    int verbose;          /* progress lines on stderr (0 quiet, 1 progress, 2 debug) */
} glpgp_options;

/* Fill the documented defaults. */
void glpgp_options_default(glpgp_options *o);

typedef struct glpgp_level_stats {
    double eps;
    int newton;          /* Newton iterations at this level */
    long cg;             /* CG iterations at this level */
    double grad0, grad;  /* gradient norm at start / end */
    double energy;       /* E + P at the end */
    double median_zabs;
    int restarted;       /* the level collapsed (median |z| < 0.5) and was restarted */
    int fallbacks;       /* mixed-Hessian steps redone with the projected Hessian */
} glpgp_level_stats;

typedef struct glpgp_osc_result {
    double *z;                 /* 2*nv: Re, Im per vertex */
    unsigned char *dirichlet;  /* nv flags */
    int n_dirichlet;
    signed char *singular;     /* nt: winding -1, 0, +1 */
    int plus, minus;           /* singular triangle counts */
    double zabs_min, zabs_p10, zabs_median;
    double energy;             /* final E (quadratic part) */
    int newton_iterations;     /* total over levels */
    long cg_iterations;        /* total, including the naive/initial solve */
    int nlevels;
    glpgp_level_stats level[GLPGP_MAX_LEVELS];
    double seconds;
} glpgp_osc_result;

typedef struct glpgp_result {
    int nv, nt;
    double size;               /* h actually used */
    double *field;             /* 2*nv: U (V = U rotated by +90 degrees) */
    glpgp_osc_result osc[2];   /* 0: u, 1: v */
    const char *backend;       /* backend name */
    double seconds_setup, seconds_field, seconds_total;
    long field_cg_iterations;
} glpgp_result;

/* Run the whole pipeline on mesh m with backend b (already created; setup is
 * done here). On success *out holds the result (free with
 * glpgp_result_destroy). Progress goes to stderr when o->verbose. */
glpgp_status glpgp_solve(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                         glpgp_result **out);
void glpgp_result_destroy(glpgp_result **r);

/* Default h for a mesh: diagonal of its bounding box / 20, raised to 10 mean
 * edge lengths when the mesh is too coarse for that. */
double glpgp_default_size(const glpgp_mesh *m);

/* Lower-level pieces, exposed for tests and crosscheck. */

/* Guiding field U (2*nv) for option o (boundary/radial/file). */
glpgp_status glpgp_field_compute(const glpgp_mesh *m, glpgp_backend *b, const glpgp_options *o,
                                 double *u, long *cg_iterations);
/* Dirichlet flags of oscillator field w (2*nv): boundary vertices where, for
 * one of the two adjacent boundary edges, |w.n| >= |w.t|. Returns the count. */
int glpgp_dirichlet_set(const glpgp_mesh *m, const double *w, unsigned char *dir);
/* Per-triangle windings of z (2*nv) into sing (nt); counts into *plus, *minus. */
void glpgp_singularities(const glpgp_mesh *m, const double *z, signed char *sing, int *plus,
                         int *minus);

/* State of the Newton iteration at one eps level (vectors of 2*nv doubles). */
typedef struct glpgp_newton_state {
    glpgp_vec *x;    /* iterate (updated by a step) */
    glpgp_vec *g;    /* gradient of E + P at x (input of a step) */
    glpgp_vec *d, *xt, *work; /* scratch */
    double grad0;    /* |g| at the start of the level */
    int near;        /* exact-Hessian switch of `mixed` (start at 0) */
    int cooldown;    /* steps left before `mixed` may try the exact Hessian again */
} glpgp_newton_state;

typedef struct glpgp_newton_step_info {
    int cg;          /* CG iterations (all attempts) */
    int fallbacks;   /* Hessians abandoned for a safer one */
    int accepted;    /* the line search found a descent step */
    double alpha;    /* accepted step length (0 when none) */
    double energy;   /* E + P at the new x */
} glpgp_newton_step_info;

/* One modified Newton step at x (the driver of glpgp_solve, exposed for the
 * benchmark): assemble (H_E + H~_P(x)), solve it by PCG to the inexact-Newton
 * tolerance, backtrack on E + P, update x. Needs QUAD assembled and
 * s->g = grad(E+P)(x) with F = (E+P)(x) and gn = |g|. */
glpgp_status glpgp_newton_step(glpgp_backend *b, const glpgp_options *o, glpgp_newton_state *s,
                               double inv4e2, double F, double gn, glpgp_newton_step_info *info);

/* Jacobi-PCG on the backend's NEWTON matrix: solves NEWTON x = rhs from x = 0.
 * Returns the iteration count in *iters and the final relative residual in
 * *relres. Work vectors are created and destroyed inside. */
glpgp_status glpgp_cg(glpgp_backend *b, const glpgp_vec *rhs, glpgp_vec *x, double rtol,
                      int maxit, int check, int *iters, double *relres);

#endif
