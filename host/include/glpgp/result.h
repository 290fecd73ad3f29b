/* glpgp/result.h: the result of a solve: the guiding field, and per
 * oscillator (u, v) its values z, Dirichlet set, singular triangles, |z|
 * statistics, iteration counts and the per-eps-level statistics of the
 * continuation. Produced by glpgp_solve (glpgp/solve.h) or read back from a
 * result file (glpgp/io.h). Layer: solver. */
#ifndef GLPGP_RESULT_H
#define GLPGP_RESULT_H

#include "glpgp/mesh.h"
#include "glpgp/timers.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GLPGP_MAX_LEVELS 32

typedef struct glpgp_level_stats {
    double eps;
    int newton;          /* Newton iterations at this level */
    long cg;             /* CG iterations at this level */
    double grad0, grad;  /* gradient norm at start / end */
    double energy;       /* E + P at the end */
    double median_zabs;
    int restarted;       /* the level collapsed (median |z| < collapse_zabs) and was restarted */
    int fallbacks;       /* Newton steps redone with a safer Hessian */
    int backtracked;     /* trust-region steps shortened along d (ratio test failed at full length) */
    int capped;          /* the level stopped at newton_max with |g| above its tolerance */
    int at_noise;        /* the level stopped with |g| above its tolerance because no step
                            decreases E + P measurably any more (the line search found none,
                            or the trust-region model promises less than F's rounding
                            level): converged as far as double precision resolves */
    int stalled;         /* the level stopped with |g| above its tolerance because E + P fell
                            by at most ftol |E + P| over 3 Newton steps (the cross field's
                            --cross-ftol: slow drift of singularities on near-neutral modes;
                            the oscillators' --newton-ftol: a plateau where the trust region
                            no longer lowers |g|) */
    double rtol;         /* the level's tolerance |g| <= rtol |g0| */
    int cg_capped;       /* Newton linear solves stopped by the CG cap (cg_max) */
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
    int capped_levels;         /* levels that stopped at the Newton cap */
    double seconds;
} glpgp_osc_result;

typedef struct glpgp_result {
    int nv, nt;
    double size;               /* h actually used */
    double *field;             /* 2*nv: U (V = U rotated by +90 degrees) */
    glpgp_osc_result osc[2];   /* 0: u, 1: v */
    const char *backend;       /* backend name (static string) */
    double seconds_setup, seconds_field, seconds_total;
    long field_cg_iterations;
    long host_round_trips;     /* blocking scalar reads the drivers made (b->n_sync) */
    long kernel_launches;      /* device kernels enqueued (b->n_launch; 0 without OpenCL) */
    glpgp_timers timers;       /* where the time went, per phase (glpgp/timers.h): the solve's
                                  phases (with concurrent oscillators both threads' sums);
                                  the command line adds its own (read, outputs) */
    int concurrent;            /* 1: u and v were solved at the same time, v on a clone of the
                                  backend in a second host thread (glpgp_options.oscillators) */
    struct glpgp_cross_result *cross; /* the cross field of --field cross (glpgp/cross.h), else NULL */
    int coupled;               /* 1: osc[0], osc[1] were solved coupled across the cuts of the
                                  representatives `field` (glpgp/cross.h): z stays per vertex in
                                  each vertex's own frame, and a triangle's (u, v) is read through
                                  its corners' matching (glpgp_coupled_frame_value); osc[0]
                                  carries the coupled solve's statistics and energy E_u + E_v,
                                  osc[1] zeros; singular = the frame windings */
} glpgp_result;

/* A zeroed result for nv vertices and nt triangles with field, z,
 * dirichlet and singular arrays allocated (zeros). */
glpgp_status glpgp_result_create(int nv, int nt, glpgp_result **out);
void glpgp_result_destroy(glpgp_result **r);

/* Per-triangle windings of z (2*nv) into sing (nt, may be NULL); counts into
 * *plus, *minus (glpgp/phase.h conventions). */
void glpgp_singularities(const glpgp_mesh *m, const double *z, signed char *sing, int *plus,
                         int *minus);

/* Bring a result computed on a renumbered mesh (vertex i of the input was
 * vertex new_of_old[i] there, glpgp_mesh_renumber) back to the input's
 * numbering: a[i] <- a'[new_of_old[i]] for every per-vertex array (field, z,
 * Dirichlet flags, the cross field's w); per-triangle arrays and counts are
 * unchanged (triangles keep their order). */
glpgp_status glpgp_result_permute_vertices(glpgp_result *r, const int *new_of_old);

/* Recompute o->singular, plus, minus and the |z| statistics from o->z. */
glpgp_status glpgp_osc_summarize(const glpgp_mesh *m, glpgp_osc_result *o);

#ifdef __cplusplus
}
#endif

#endif
