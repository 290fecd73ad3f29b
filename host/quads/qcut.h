/* quads/qcut.h: the cut mesher (qcut.c): an all-quad mesh of a polygonal
 * region with holes whose boundary points are all kept, by recursive
 * straight cuts. Used by the repair for the regions it re-meshes and for
 * the whole domain. Internal to the quads layer. */
#ifndef GLPGP_QUADS_QCUT_H
#define GLPGP_QUADS_QCUT_H

#include "qvec.h"

/* A region: loops of point ids (outer loops counter-clockwise, holes
 * clockwise: the region on the left of every loop), and for each loop the
 * outer loop it belongs to. */
typedef struct qcut_region {
    int nloops;
    const int *loop_start; /* nloops + 1 */
    const int *loop_v;     /* point ids into the caller's xy */
    const int *owner;      /* per loop: -1 for an outer loop, else the index of its outer loop */
    double max_work;       /* the cut searches' bound, in loop points squared (0: none) */
} qcut_region;

typedef struct qcut_stats {
    int pieces;  /* pieces meshed by a split or a template */
    int cuts;    /* straight cuts made (hole cuts included) */
    int points;  /* new points (on cuts, template centers) */
    double work; /* the cut searches' work (loop points squared) */
} qcut_stats;

/* Mesh R with quads. xy: the points (2 per point), grown with the new ones;
 * quads: 4 point ids per quad appended (counter-clockwise). Every outer
 * loop with its holes must have an even number of loop points in all (a
 * quad mesh of a region has an even number of boundary edges). The quads
 * are about h where the loops' edges are (the size grows from each loop
 * edge's length towards h, at most h). GLPGP_ERR_NUMERIC when a piece has
 * an odd count or could not be cut or split into quads with positive
 * corners (the caller falls back); GLPGP_ERR_NOMEM. */
glpgp_status glpgp_qcut_mesh(dvec *xy, const qcut_region *R, double h, ivec *quads, qcut_stats *stats);

#endif
