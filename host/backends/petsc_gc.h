/* backends/petsc_gc.h: the global coarse space of the PETSc backend's
 * multigrid with more than one rank (petsc_gc.c), shared by petsc_amg.c
 * (the cycle's ops call it on the fine level) and petsc_gc.c. Part of the
 * module glpgp_petsc.so; not installed.
 *
 * Below the fine level each rank's hierarchy is its own (block Jacobi
 * across ranks). The fine level's coarse correction adds a global term
 * Z E^+ Z^T, E = Z^T A Z, whose columns are, for each rank s and each
 * aggregate K of one level k of s's hierarchy, the composed prolongation
 * from K down to s's owned vertices (2 real columns per node: z and i z).
 * Level k is the finest whose nodes over all ranks number at most
 * `-glpgp_mg_global N`; none (N = 0, the default, or too many ranks): one
 * node per rank, the level-0 frame, added to the local correction (the
 * first version, bit for bit). With k > 0 the term is applied before and
 * after the local coarse levels (the balancing form, symmetric). */
#ifndef GLPGP_PETSC_GC_H
#define GLPGP_PETSC_GC_H

#include "petsc_impl.h"

typedef struct pm_gc {
    int P;            /* ranks */
    int k;            /* the level whose aggregates are Z's columns (0: one node per rank, the frame) */
    int ms, M, moff;  /* this rank's nodes, all ranks', this rank's first */
    int *node;        /* per owned vertex: this rank's node (-1: none) */
    int *gidx;        /* per system vertex: the global node of its owner's column (-1: none) */
    double *zeta;     /* 2 per owned vertex: Z's complex entry */
    int *ecnt, *edsp; /* per rank: E's rows in doubles (all-gather) */
    int *ycnt, *ydsp; /* per rank: the restrictions' doubles */
    double *eloc;     /* this rank's 2 ms rows of E (2M columns) */
    double *e;        /* E, 2M x 2M row-major */
    int *erp, *ecol;  /* E as a dense block CSR of M nodes */
    double *eval;
    double *einv, *ew; /* E's generalised inverse, its work */
    int *ei;
    double *yl;       /* 2 ms: Z_s^T t, then this rank's rows of E^+ Z^T t */
    double *g;        /* 2M: Z^T t, all ranks */
    Vec zv;           /* a distributed Vec for the ghost exchanges */
    double *tbuf;     /* 2 per owned vertex: the fine residual */
    double *tbuf2;    /* 2 per owned vertex: Z y */
    double *ysave;    /* 2 ms */
} pm_gc;

/* The space from the rank's hierarchy: L levels, agg[l] the aggregate of
 * each node of level l (level 0: each system vertex, -1 off the rank),
 * n[l] the level sizes. Collective. */
glpgp_status glpgp_petsc_gc_create(pimpl *p, int L, const int *const *agg, const int *n, pm_gc **out);
void glpgp_petsc_gc_destroy(pm_gc **g);

/* Z's entries and E from the levels' prolongation weights c[l] (level 0
 * indexed by system vertex) and the level-0 frame (NULL: 1). Collective. */
glpgp_status glpgp_petsc_gc_values(pimpl *p, pm_gc *g, const int *const *agg, const double *const *c,
                                   const glpgp_vec *frame);

/* E's generalised inverse (spd: the symmetric one); 0, or 1 on a non-finite E */
int glpgp_petsc_gc_invert(pm_gc *g, int spd);

/* yl += Z_i^T t for owned vertex i (the restriction's rows) */
static inline void glpgp_petsc_gc_add(pm_gc *g, int iown, double t0, double t1)
{
    const int nd = g->node[iown];
    if (nd < 0) return;
    const double zr = g->zeta[2 * iown], zi = g->zeta[2 * iown + 1];
    g->yl[2 * nd] += zr * t0 + zi * t1;
    g->yl[2 * nd + 1] += -zi * t0 + zr * t1;
}

/* yl <- this rank's rows of E^+ Z^T t (the restrictions all-gathered) */
glpgp_status glpgp_petsc_gc_solve(pm_gc *g);

/* xf[1] <- own (2 doubles per owned vertex) at the owned and ghost vertices */
glpgp_status glpgp_petsc_gc_exchange(pimpl *p, pm_gc *g, const double *own);

/* xf[1] <- Z yl at the owned and ghost vertices (one exchange) */
glpgp_status glpgp_petsc_gc_zy(pimpl *p, pm_gc *g);

/* x_i += Z_i yl for the owned vertices (x indexed by system vertex) */
void glpgp_petsc_gc_prolong(const pimpl *p, const pm_gc *g, double *x);

#endif
