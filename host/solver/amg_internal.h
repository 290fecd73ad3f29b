/* solver/amg_internal.h: what the multigrid's two files share
 * (solver/amg_structure.c builds the hierarchy structure once per system,
 * solver/amg.c instantiates it on a backend and runs the cycle): the
 * structure's layout. */
#ifndef GLPGP_SOLVER_AMG_INTERNAL_H
#define GLPGP_SOLVER_AMG_INTERNAL_H

#include "internal.h"

/* A weighted graph in CSR form (no self loops). */
typedef struct wgraph {
    int n;
    int *ptr, *adj;
    double *wt;
} wgraph;

/* One level of the structure. */
typedef struct amg_slevel {
    int n;
    long nnzb;
    int *rowptr, *col, *diag; /* levels >= 1 (level 0: the system's) */
    int *agg, *aptr, *amem;   /* transfer to l+1 (levels < L-1); every node in one aggregate */
    int *gptr, *gsrc;         /* Galerkin map of A_{l+1} (glpgp/backend.h, glpgp_amg_level) */
    double *pos;              /* 2n: node positions (level 0) and aggregate centroids */
} amg_slevel;

struct glpgp_amg_structure {
    const glpgp_system *sys;  /* the system it was built for (borrowed) */
    int coarse, max_levels;   /* the options it was built with (o->amg_coarse, amg_max_levels) */
    int L;
    amg_slevel lev[GLPGP_AMG_MAX_LEVELS];
    double operator_complexity, grid_complexity;
    double seconds;           /* its construction */
};

#endif
