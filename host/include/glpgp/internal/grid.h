/* glpgp/internal/grid.h: a uniform 2D grid of axis-aligned boxes for
 * neighbour queries (core/grid.c): every item (a segment, a face, a loop)
 * is listed in each cell its box overlaps (CSR), and a query returns the
 * items whose box may overlap a rectangle, each once, in cell order. Used by
 * the quad checks and repair, the cut mesher and the mask contours.
 * Internal: not installed. Layer: core. */
#ifndef GLPGP_INTERNAL_GRID_H
#define GLPGP_INTERNAL_GRID_H

#include "glpgp/status.h"

typedef struct glpgp_bgrid {
    double x0, y0, cs;
    int nx, ny;
    int *start, *item; /* CSR: cell -> items */
    int *stamp, tick;  /* per item: last query that returned it */
    int nitems;
} glpgp_bgrid;

/* box[4 i .. 4 i + 3] = xmin, ymin, xmax, ymax of item i. cs: cell size hint
 * (<= 0: one cell); the cells are made larger until there are at most about
 * 2 n + 16 of them. */
glpgp_status glpgp_bgrid_build(glpgp_bgrid *g, const double *box, int n, double cs);
void glpgp_bgrid_free(glpgp_bgrid *g);
/* Items whose box may overlap [x0, x1] x [y0, y1] (each once) into *out
 * (grown as needed, *cap its capacity); returns their count or -1 on OOM. */
int glpgp_bgrid_query(glpgp_bgrid *g, double x0, double y0, double x1, double y1, int **out, int *cap);

#endif
