/* quads/repair.h: the parts of the repair (glpgp_quadmesh_repair), private
 * to the quads layer:
 *  - region.c: the domain boundary as parametrised loops (dbnd) and the
 *    regions to re-mesh: the polygons between the kept faces and the domain
 *    boundary (region);
 *  - trisplit.c: the fallback fill of a region (a triangulation of it, each
 *    triangle split into 3 or 5 convex quads);
 *  - repair.c: the rounds, the region mesher (qcut.c) with that fallback,
 *    and the output (rbuild);
 *  - lastresort.c: whole-domain meshes when the local repair does not end
 *    valid, down to the input's own triangles split into quads. */
#ifndef GLPGP_QUADS_REPAIR_H
#define GLPGP_QUADS_REPAIR_H

#include "check.h"
#include "qvec.h"

/* ---- the domain boundary as loops with a parameter (region.c) --------------- */

typedef struct dbnd {
    const glpgp_mesh *m;
    bgrid G;      /* boundary segments */
    int nb;       /* segments = loop vertices */
    int *loop_of; /* segment -> loop */
} dbnd;

glpgp_status glpgp_dbnd_build(dbnd *D, const glpgp_mesh *m, double h);
void glpgp_dbnd_free(dbnd *D);
/* Nearest boundary point within r of p: its segment (-1: none), parameter
 * *t on it, distance and projection (*cand, *ncap: query scratch). */
int glpgp_dbnd_nearest(dbnd *D, const double *p, double r, double *t, double *dist, double *proj, int **cand,
                       int *ncap);

/* ---- regions (region.c) ------------------------------------------------------- */

/* Region half-edge a -> b; kind 1: an edge of the kept faces (interface),
 * 2: a piece of the domain boundary (p0, p1: loop parameters of the ends on
 * domain loop `loop`, for the split point). */
typedef struct rhe {
    int a, b, kind, used;
    double p0, p1;
    int loop;
} rhe;

/* The regions of one repair round: the domain minus the kept faces (K),
 * as loops of half-edges. Point ids: 0 .. q->nv - 1 are the mesh's, the
 * new boundary points follow (vxy). Outer loops (area > 0) own the holes
 * (area < 0) inside them. */
typedef struct region {
    const glpgp_quadmesh *q;
    const glpgp_mesh *m;
    dbnd *D;
    double h;
    dvec vxy;       /* the points after the mesh's */
    rhe *he;
    int nhe, cap;
    int nloops;
    int *loop_start; /* nloops + 1 into loopv */
    ivec loopv;      /* half-edge ids */
    double *area;    /* per loop */
    int *owner;      /* per hole: its outer loop; -1 for outer loops (and stray holes) */
} region;

/* Build the regions of q without the faces flagged in inB. */
glpgp_status glpgp_region_build(region *R, const glpgp_quadmesh *q, const glpgp_mesh *m, dbnd *D, double h,
                                const unsigned char *inB);
void glpgp_region_free(region *R);
const double *glpgp_region_xy(const region *R, int v);
/* The split point of a domain-boundary half-edge (an input boundary vertex
 * near the middle of its parameter range, else the middle). */
void glpgp_region_split_point(const region *R, const rhe *e, double *out);
/* Make the loops of outer loop O and its holes even: the longest domain
 * boundary half-edge is split at its split point (a new point); when there
 * is none, the longest interface half-edge is split at its middle and
 * *kedge receives its ends (a, b) and *kmid the new point (the kept face on
 * its other side gets that point too); else *kmid = -1. */
glpgp_status glpgp_region_make_even(region *R, int O, int *kedge, int *kmid);

/* ---- the output of a round ------------------------------------------------------- */

typedef struct rbuild {
    dvec xy;     /* output vertices */
    ivec fs, fv; /* faces: start offsets (nf + 1) and corners */
    ivec fo;     /* per face: origin GLPGP_QFACE_* */
    ivec newv;   /* vertices added by the repair */
} rbuild;

glpgp_status glpgp_rbuild_face(rbuild *R, const int *v, int n, int origin);
glpgp_status glpgp_rbuild_vertex(rbuild *R, double x, double y, int *id);
void glpgp_rbuild_free(rbuild *R);

/* ---- the fallback fill (trisplit.c) -------------------------------------------- */

/* Fill outer loop O of R (with its holes) with quads: constrained Delaunay
 * triangulation of the loops, inner edges longer than 2.6 h bisected, every
 * triangle split into 3 or 5 convex quads without splitting an interface
 * half-edge (parity by paths in the dual graph). Region point v is output
 * vertex gid[v] (gid has room for every region point; -1: not yet in B,
 * then added). A parity defect left stays a pentagon. *nquads: quads made. */
glpgp_status glpgp_trisplit_fill(const region *R, int O, int *gid, rbuild *B, int origin, int *nquads);

/* ---- whole-domain meshes (lastresort.c) ---------------------------------------------- */

/* *out: an all-quad mesh of the whole domain m at size h that the quality
 * check accepts, from the first of: the cut mesher on the domain's loops,
 * the triangulation fill, the input triangles coarsened by edge collapses
 * and split into quads, the input triangles split into quads (valid for
 * every valid triangle mesh); *level: 1 .. 4, which one. *out NULL when
 * even the last is rejected (a broken input: the report says why). */
glpgp_status glpgp_quads_last_resort(const glpgp_mesh *m, double h, glpgp_quadmesh **out, int *level);

/* ---- boundary chords (chords.c) ------------------------------------------------------ */

/* An all-quad mesh whose boundary chords cut off more than 0.6% of the
 * domain's area: strips of quads cut in two across the mesh between the
 * boundary edges that lose the most, their ends moved onto the domain
 * boundary (new grid lines). *nstrips: strips made. Other meshes are left
 * alone. */
glpgp_status glpgp_quadmesh_chord_strips(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *nstrips);

/* The sides of an all-quad mesh (face_start[f] = 4 f) sorted by edge, to
 * find the face across a side. */
typedef struct qsides {
    struct chord_hedge *h;
    int n;
} qsides;
glpgp_status glpgp_qsides_build(const glpgp_quadmesh *q, qsides *S);
void glpgp_qsides_free(qsides *S);
/* The face across side i (corners i, i + 1) of face f, its side there in
 * *j; -1 on the boundary. */
int glpgp_qsides_across(const qsides *S, const glpgp_quadmesh *q, int f, int i, int *j);
/* The strip entering face f0 through side i0 and leaving each quad through
 * the opposite side: faces and entry sides into path (2 ints a face, room
 * for 2 nf), the boundary side where it ends in *fe, *ie. 0 when it meets
 * a face marked in seen (itself included: seen is restored) or a non-quad. */
int glpgp_quadmesh_strip_trace(const qsides *S, const glpgp_quadmesh *q, int f0, int i0, int *path, int *len, int *fe,
                           int *ie, unsigned char *seen);
/* The domain boundary between the ends of boundary edge a -> b: the area
 * between it and the chord (*loss) and the boundary point half-way along
 * (*mid); 0 when a or b is not on the boundary, they are on different loops
 * or the arc spans over half its loop. */
int glpgp_dbnd_chord(dbnd *D, const double *a, const double *b, double h, double *loss, double *mid, int **cand,
                     int *ncap);

/* ---- the last shape pass (shape.c) -------------------------------------------------- */

/* Sharp tips re-meshed with one strip, flat boundary corners split with
 * two strips, then the optimisation smoothing around quads below 0.5
 * (shape.c's header); q changed in place. *tips, *flat: tips and corners
 * fixed, *moved: vertices moved. The caller keeps the
 * result only when it is as valid as before. */
glpgp_status glpgp_quadmesh_shape_pass(glpgp_quadmesh *q, const glpgp_mesh *m, double h, int *tips, int *flat,
                                       int *moved);

/* ---- shared helpers (repair.c) ---------------------------------------------------- */

/* The repair rounds alone (at most rounds, no last resort), smooth sweeps:
 * *out the mesh after them (valid or not). */
glpgp_status glpgp_repair_rounds(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, int smooth, int rounds,
                                 glpgp_quadmesh **out);

/* A copy of q (arrays and face origins; diagnostics kept). NULL: no memory. */
glpgp_quadmesh *glpgp_qm_copy(const glpgp_quadmesh *q);
/* q's arrays replaced by an all-quad mesh's: points *xy (nv), corners *fv
 * (4 nf), origins *fo, and *fs (room for nf + 1, filled here); the old
 * arrays freed, the caller's pointers set to NULL. */
void glpgp_qm_adopt_quads(glpgp_quadmesh *q, double **xy, int nv, int **fv, int **fs, unsigned char **fo, int nf);

#endif
