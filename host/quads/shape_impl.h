/* quads/shape_impl.h: what the last shape pass's two files share (quad
 * layer only): shape.c (corner measure, vertex stars, the optimisation
 * smoothing, strips across the mesh, flat boundary corners, the rule that
 * keeps a change) and tips.c (sharp tips). */
#ifndef GLPGP_QUADS_SHAPE_IMPL_H
#define GLPGP_QUADS_SHAPE_IMPL_H

#include "repair.h"

#define SHAPE_BELOW 0.5     /* the smoothing works around quads below this */
#define SHAPE_FLAT_MAX 64   /* flat corners (and tips) fixed per pass at most */
#define SHAPE_FLAT_NEW 0.05 /* a change's new quads above this before the smoothing */

/* Scaled Jacobian of corner i of polygon v[0..n-1] (counter-clockwise). */
double glpgp_shape_corner_sj(const double *xy, const int *v, int n, int i);

/* Each vertex's corners in the faces (CSR). */
typedef struct vstar {
    int *vs, *vc; /* vertex -> corner slots (CSR) */
    int *sf;      /* slot -> face */
} vstar;
glpgp_status glpgp_vstar_build(const glpgp_quadmesh *q, vstar *S);
void glpgp_vstar_free(vstar *S);

/* Strips of quads cut in two across the mesh (at most two; a quad crossed
 * twice at right angles is cut in four). */
typedef struct flat_fix {
    int Q, i;              /* the face and c's corner in it */
    int *path[2], len[2];  /* the strips from sides (a, b) and (d, a): faces and entry sides */
    int loop;              /* 1: one strip from (a, b) that comes back through (d, a) */
    int ncross;            /* faces crossed twice, at right angles (each cut in four) */
    int *pos[2];           /* per face: its first and second pass, 2 t + k (step t of strip k), or -1 */
    double end[2][2];      /* the strips' ends on the domain boundary */
} flat_fix;
/* Strip k from face f0 entered through side i0 (shape.c has the rules); 1:
 * it reached the boundary (side *ie of face *fe), 2: it came back into F->Q
 * through side qside, 0: neither. */
int glpgp_shape_trace(const qsides *S, const glpgp_quadmesh *q, flat_fix *F, int k, int f0, int i0, int qside, int *fe,
                      int *ie);
/* The origin a face cut or split by the pass gets. */
unsigned char glpgp_shape_split_origin(const glpgp_quadmesh *q, int f);
/* The first nk strips' points into xy from s0[k]; the cut faces marked. */
void glpgp_shape_strip_points(const glpgp_quadmesh *q, const flat_fix *F, int nk, const int *s0, double *xy,
                              unsigned char *cut);
/* The cut faces' halves (quarters where crossed, centers from X) into fv /
 * fo from slot *w; their worst corner. */
double glpgp_shape_strip_halves(const glpgp_quadmesh *q, const flat_fix *F, const int *s0, int X, double *xy, int *fv,
                                unsigned char *fo, int *w);

/* The arrays of a changed all-quad mesh (points, corners, face starts and
 * origins) and a flag per face of the old one (cut or removed). */
typedef struct shape_arrays {
    double *xy;
    int *fv, *fs;
    unsigned char *fo, *cut;
} shape_arrays;
glpgp_status glpgp_shape_arrays_alloc(const glpgp_quadmesh *q, int nv, int nf, shape_arrays *N);
void glpgp_shape_arrays_free(shape_arrays *N);

/* A change applied by commit, the mesh smoothed, kept only when better
 * (shape.c: by the raw measure with m NULL, by the corners' measure with m). */
typedef glpgp_status (*shape_commit)(glpgp_quadmesh *q, const void *fix, int *done, double *worst);
glpgp_status glpgp_shape_try(glpgp_quadmesh *q, shape_commit commit, const void *fix, const glpgp_mesh *m, double h,
                             int *done, double *worst, int *nmoved);

/* Sharp tips (tips.c): *nfixed re-meshed, *nmoved vertices moved. */
glpgp_status glpgp_shape_tips(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *nfixed, int *nmoved);

#endif
