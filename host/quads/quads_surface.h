/* quads/quads_surface.h: the quad layer's surface files (extract_surface.c,
 * check_surface.c, quads_surface.c); their entry points are in
 * glpgp/quads.h. Internal to the quads layer. */
#ifndef GLPGP_QUADS_SURFACE_H
#define GLPGP_QUADS_SURFACE_H

#include "glpgp/quads.h"
#include "glpgp/status.h"

/* Move the points xyz[3 first .. 3 n) to their nearest points on surface m
 * (those within 2 h of it; check_surface.c). */
glpgp_status glpgp_qs_project(const glpgp_mesh *m, double h, double *xyz, int first, int n);

/* Nearest points on the input surface through a grid of cells
 * (check_surface.c): create for surface m at size h with distances capped
 * at cap; nearest: x = the nearest point of m to p within the cap (p
 * itself when none), returns its triangle (-1: none); normal: triangle
 * t's unit normal (m->surf->tframe). */
typedef struct glpgp_qs_proj glpgp_qs_proj;
glpgp_status glpgp_qs_proj_create(const glpgp_mesh *m, double h, double cap, glpgp_qs_proj **out);
int glpgp_qs_proj_nearest(const glpgp_qs_proj *P, const double *p, double *x);
const double *glpgp_qs_proj_normal(const glpgp_qs_proj *P, int t);
void glpgp_qs_proj_destroy(glpgp_qs_proj **P);

/* Points in two arrays (the local repair's: the quad mesh's, then the new
 * ones): n in all, id < nbase at base + 3 id, the others at
 * ext + 3 (id - nbase). */
typedef struct glpgp_qs_pts {
    const double *base;
    double *ext;
    int nbase, n;
} glpgp_qs_pts;

static inline const double *glpgp_qs_pt(const glpgp_qs_pts *S, int id)
{
    return id < S->nbase ? S->base + 3 * id : S->ext + 3 * (id - S->nbase);
}

/* Scaled Jacobians in a quad's own plane (untangle_surface.c; the plane
 * and the corners as glpgp_quadmesh_face_sj_surface measures them, through
 * the Newell normal): quad_sj: the worst corner of the quad whose corners
 * are p[0..3], -1 when it is degenerate or against the surface's normal
 * at its centroid (the triangle of P nearest to it); worst_sj: the worst
 * corner of nq quads (4 ids of S each), 1 when nq is 0. */
double glpgp_qs_quad_sj(const glpgp_qs_proj *P, const double *const p[4]);
double glpgp_qs_worst_sj(const glpgp_qs_proj *P, const glpgp_qs_pts *S, const int *quads, int nq);

/* The untangling of lifted quads (untangle_surface.c; the local repair's
 * of a lift that tangled a few corners): while *worst, their worst corner
 * (glpgp_qs_worst_sj; on entry that of the quads as given), is at or below
 * floor_sj, at most max_sweeps Laplacian sweeps of S's points from id
 * first on: each to the mean of its edge neighbours in the nq quads (4 ids
 * each; the points at no quad stay), then to its nearest point on P's
 * surface. Points below first stay; S->nbase <= first <= S->n (the
 * moving points are in S->ext), else GLPGP_ERR_ARG. *worst: the worst
 * corner after. How tangled a lift may be mended is the caller's call. */
glpgp_status glpgp_qs_untangle(const glpgp_qs_proj *P, const glpgp_qs_pts *S, int first, const int *quads, int nq,
                               int max_sweeps, double floor_sj, double *worst);

/* The closing of the extraction's polygons (close_surface.c): odd faces
 * paired across a side and even faces split (glpgp_qs_close_pairs: *out
 * NULL when nothing was closed; *closed the faces made quads), and the
 * odd faces left joined by strips and closed (glpgp_qs_strips_closed:
 * *out the all-quad result with the fewest irregular interior vertices,
 * NULL when none; the new points moved onto m). */
glpgp_status glpgp_qs_close_pairs(const glpgp_mesh *m, double h, const glpgp_quadmesh *q, glpgp_quadmesh **out,
                                  int *closed);
glpgp_status glpgp_qs_strips_closed(const glpgp_mesh *m, double h, const glpgp_quadmesh *q, glpgp_quadmesh **out,
                                    int *nstrips, int *nclosed);
/* Interior vertices of valence other than 4 (-1 without memory); faces that are not quads. */
int glpgp_qs_irregular_interior(const glpgp_quadmesh *q);
int glpgp_qs_count_nonquads(const glpgp_quadmesh *q);

/* A surface quad mesh's arrays (xyz, xy, face_start, face_vert, face_origin
 * zeroed) for nv points, nf faces and ncorner corners (quads_surface.c). */
glpgp_status glpgp_qs_alloc(int nv, int nf, int ncorner, glpgp_quadmesh **out);
/* r made from q: its plane coordinates (x, y of xyz) and q's singularity counts. */
void glpgp_qs_finish_from(glpgp_quadmesh *r, const glpgp_quadmesh *q);

/* Triangles tri (nt, ids of the np points xyz) split into three quads each
 * (corner, side midpoint, centroid, side midpoint; origin FALLBACK): the
 * points, then one per side, then the centroids, none moved
 * (quads_surface.c: the input's triangles; coarse_surface.c: the coarse ones). */
glpgp_status glpgp_qs_split_triangles(const double *xyz, int np, const int *tri, int nt, glpgp_quadmesh **out);

/* The local repair (repair_surface.c): q's bad faces (not quads, inverted,
 * non-manifold, pinched; with far, over 0.22 h from the surface) and their neighbours
 * removed in regions grown to topological disks, each flattened onto a
 * plane, meshed by the cut mesher with its boundary points fixed and lifted
 * onto the surface; the other faces kept. *out NULL when q has no bad face
 * or no region could be repaired (when some could: those, the others' faces
 * kept); *rs: the regions. The caller checks the result. */
glpgp_status glpgp_qs_local_repair(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far,
                                   glpgp_quadmesh **out, glpgp_quads_repair *rs);

/* The faces the local repair takes as bad (bad[f] = 1; repair_surface.c; far: with the
 * faces far from the surface); *nbad their count. */
glpgp_status glpgp_qs_bad_faces(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, int far, unsigned char *bad,
                                int *nbad);

/* The local split (split_surface.c): the faces of sel (and those not quads)
 * split in n quads each (Catmull-Clark), the quad strips through their
 * sides split in two along the strip until they close (a quad crossed by
 * two strips split in four): a conforming all-quad mesh with q's topology;
 * the new points moved onto the surface. *nsplit: the faces of q split. */
glpgp_status glpgp_qs_split_local(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const unsigned char *sel,
                                  glpgp_quadmesh **out, int *nsplit);

/* sel[f] = 1 for the faces of q nearest to a point of surface m farther
 * than thr from q (the check's samples of m; the surface-to-quads side of
 * the Hausdorff distance, check_surface.c); *n: the faces newly marked. */
glpgp_status glpgp_qs_mark_uncovered(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, double thr,
                                     unsigned char *sel, int *n);

/* The local 3-refinement (refine3_surface.c): the faces of sel split 3 x 3,
 * the quads around them by transition templates (Schneiders), conforming
 * and all-quad with q's topology, the refinement kept local (no strips);
 * the new points moved onto the surface. *out NULL when q has faces other
 * than quads or sel is empty; *nref: the faces of q refined. */
glpgp_status glpgp_qs_refine3(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const unsigned char *sel,
                              glpgp_quadmesh **out, int *nref);

/* Flat boundary corners (split_surface.c): flat[f] <- the corner of quad f
 * at a boundary vertex in no other face that is obtuse with a scaled
 * Jacobian below goal (the worst such corner; -1: none); *nflat their
 * count. glpgp_qs_split_flat: each of those quads split like a triangle
 * (three quads about a new point, the midpoints of the two sides away
 * from the corner carried along their quad strips; a flat quad that a
 * strip enters at its corner's sides is split as Catmull-Clark does):
 * conforming and all-quad, the new points moved onto the surface. */
glpgp_status glpgp_qs_find_flat(const glpgp_quadmesh *q, double goal, signed char *flat, int *nflat);
glpgp_status glpgp_qs_split_flat(const glpgp_mesh *m, const glpgp_quadmesh *q, double h, const signed char *flat,
                                 glpgp_quadmesh **out, int *nsplit);

/* glpgp_quads_surface_fallback_coarse (17 degrees, tolerant) with the
 * smallest angle a new triangle may have (degrees; unless one before was
 * smaller); tolerant 0: no relaxation, and curves collapse only where they
 * turn by under 30 degrees (the last resort's second try: coarse_surface.c). */
glpgp_status glpgp_qs_coarse(const glpgp_mesh *m, double h, double feature_deg, double amin_deg, int tolerant,
                             glpgp_quadmesh **out, int *ntri);

/* glpgp_quads_build_surface on a surface of one connected component (or on
 * all of them at once): quads_surface.c. */
glpgp_status glpgp_qs_build_one(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                                glpgp_quadmesh **out, double *h, glpgp_quads_surface_steps *steps);

#endif
