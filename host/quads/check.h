/* quads/check.h: the validity checks of a polygon mesh against its domain,
 * per face (private to host/quads/). Used by the quality report
 * (quality.c: counts and the `valid` flag) and by the local repair
 * (repair.c: which faces to remove and re-mesh). */
#ifndef GLPGP_QUADS_CHECK_H
#define GLPGP_QUADS_CHECK_H

#include "glpgp/internal/geom2.h"
#include "glpgp/internal/grid.h"
#include "glpgp/quads.h"

/* Why a face is bad (bits of the per-face flags). */
enum {
    QF_NONQUAD = 1u << 0,     /* not 4 corners */
    QF_INVERTED = 1u << 1,    /* area <= 0 in the mesh orientation, or a quad corner with SJ < 0 */
    QF_DEGENERATE = 1u << 2,  /* repeated vertex, zero-length edge or ~zero area */
    QF_NONMANIFOLD = 1u << 3, /* an edge used by > 2 faces, or twice in one direction (a fold) */
    QF_PINCHED = 1u << 4,     /* a corner at a vertex whose faces form several fans */
    QF_OVERLAP = 1u << 5,     /* an edge crosses another edge, a vertex lies inside it, or it lies inside another */
    QF_OUTSIDE = 1u << 6,     /* a vertex outside the domain or an edge crossing the domain boundary */
    QF_FAR = 1u << 7,         /* a boundary edge farther than tol from the domain boundary (gap, chord) */
    QF_LOST = 1u << 8,        /* the domain boundary passes far from the mesh boundary here (lost hole,
                               * lost corner, cut-off feature) */
    QF_FLAT = 1u << 9         /* a quad corner with scaled Jacobian below 1e-3 (repair only) */
};

typedef struct qcheck {
    int orientation;          /* +1 / -1: sign of the total signed area */
    unsigned *flags;          /* nf per-face QF_* bits (malloc'ed) */
    int nonmanifold_edges, pinched, boundary_loops;
    int corners_lost;         /* domain corners with no mesh vertex on them (-1 without domain) */
    double bnd_vertex_dist;   /* max distance of a mesh boundary vertex from the domain boundary (absolute) */
} qcheck;

/* Run every check of q (tolerance tol, absolute, for the boundary distances;
 * domain may be NULL: no domain checks). */
glpgp_status glpgp_qcheck_run(const glpgp_quadmesh *q, const glpgp_mesh *domain, double h, double tol,
                              qcheck *c);
void glpgp_qcheck_free(qcheck *c);

/* bound[f] (q->nf entries): the best smallest corner scaled Jacobian face f
 * can have at the domain's sharp corners it touches: sin(alpha) for the
 * smallest interior angle alpha < 90 degrees of a domain corner that is
 * one of its vertices (a face there has a corner of at most alpha), 1 when
 * it touches none. dm NULL: all 1. */
glpgp_status glpgp_qcheck_corner_bound(const glpgp_quadmesh *q, const glpgp_mesh *dm, double h, double *bound);
/* A face of scaled Jacobian sj below limit where its corner bound does not
 * force it (sj under 0.9 of the bound): the report's "below the goal that
 * no corner forces", the repair's and the shape pass's poor faces. */
static inline int glpgp_qcheck_unforced_below(double sj, double bound, double limit)
{
    return sj < limit && sj < 0.9 * bound;
}

/* ---- small geometry shared with repair.c: the core's (glpgp/internal/) --- */

typedef glpgp_bgrid bgrid;

#endif
