/* glpgp/timers.h: where a run's time goes. One wall-clock account per phase
 * of a run (reading, renumbering, patterns, program build, guiding field,
 * multigrid structure, per-step numeric setup, assembly, linear solves, ...),
 * exclusive (a phase nested in another is booked to itself, not twice), and
 * per phase the part of it the host spent blocked on the device (reading
 * scalars or vectors back, waiting for the queue): host work = seconds -
 * wait. The solver keeps one account per backend (glpgp_backend.tm, driven
 * by glpgp_timer_enter / _leave of glpgp/backend.h); the command line adds
 * its own phases (reading, outputs) and the statistics JSON and the summary
 * report them. Layer: core. */
#ifndef GLPGP_TIMERS_H
#define GLPGP_TIMERS_H

#ifdef __cplusplus
extern "C" {
#endif

enum glpgp_timer_id {
    GLPGP_TM_OTHER = 0,  /* inside a solve, outside every phase below */
    GLPGP_TM_READ,       /* reading the input (welding, planes; meshing an image) */
    GLPGP_TM_REFINE,     /* refinement for the local size */
    GLPGP_TM_BUILD,      /* the backend: OpenCL device, program build, first launches */
    GLPGP_TM_RENUMBER,   /* vertex renumbering (and the result back in the input's order) */
    GLPGP_TM_PATTERN,    /* block pattern and gather maps of the system */
    GLPGP_TM_UPLOAD,     /* the system's buffers on the backend, work vectors */
    GLPGP_TM_SIZE,       /* the local size field and its checks */
    GLPGP_TM_FIELD,      /* the guiding field (its own solves included) */
    GLPGP_TM_STRUCTURE,  /* multigrid hierarchy structure (aggregates, patterns, maps) */
    GLPGP_TM_NUMERIC,    /* multigrid values per Newton step (weights, Galerkin, smoothers,
                            coarsest inverse) */
    GLPGP_TM_ASSEMBLY,   /* quadratic and Newton matrices */
    GLPGP_TM_LINEAR,     /* linear solves (CG, flexible CG, Steihaug CG) */
    GLPGP_TM_ENERGY,     /* gradients, energies, trial points, model dots */
    GLPGP_TM_SUMMARY,    /* |z| statistics, singular triangles, results read back */
    GLPGP_TM_EXTRACT,    /* quad extraction and its report */
    GLPGP_TM_IMAGE,      /* the picture */
    GLPGP_TM_OUT_RESULT, /* writing --out */
    GLPGP_TM_OUT_QUADS,  /* writing --quads */
    GLPGP_TM_OUT_IMAGE,  /* writing --image */
    GLPGP_TM_COUNT
};

typedef struct glpgp_timers {
    double s[GLPGP_TM_COUNT];    /* wall seconds per phase (exclusive) */
    double wait[GLPGP_TM_COUNT]; /* of which blocked on the device */
} glpgp_timers;

/* JSON key ("program_build") and summary label ("program build") of phase id. */
const char *glpgp_timer_key(int id);
const char *glpgp_timer_label(int id);

/* 1 when phase id belongs to glpgp_solve (not to reading, the backend's
 * creation, extraction or outputs) */
int glpgp_timer_in_solve(int id);

/* a += b, phase by phase */
void glpgp_timers_add(glpgp_timers *a, const glpgp_timers *b);
/* a -= b, phase by phase (a later account minus an earlier one) */
void glpgp_timers_sub(glpgp_timers *a, const glpgp_timers *b);
/* sum of seconds (and of wait) over all phases */
double glpgp_timers_total(const glpgp_timers *t, double *wait);

#ifdef __cplusplus
}
#endif

#endif
