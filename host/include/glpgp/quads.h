/* glpgp/quads.h: quad meshes from a finished GL-PGP solve: extraction of the
 * quad mesh whose edges are the integer level lines of theta_u and theta_v
 * (quads/extract.c), closing of the polygons left around dislocations and
 * smoothing (quads/close.c), and the quality report (quads/quality.c:
 * valences, scaled Jacobian, edge lengths, boundary distance). Reading and
 * writing quad meshes and the report: glpgp/io.h. Layer: quads. */
#ifndef GLPGP_QUADS_H
#define GLPGP_QUADS_H

#include <stdio.h>

#include "glpgp/mesh.h"
#include "glpgp/optdesc.h"
#include "glpgp/result.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a face of a quad mesh comes from (glpgp_quadmesh.face_origin). A
 * face made from others takes the highest origin among them and the step
 * that made it. */
enum {
    GLPGP_QFACE_GRID = 0,     /* the parametrization's grid (the extraction) */
    GLPGP_QFACE_CLOSED = 1,   /* a grid face cut or split by the closing (strips, pentagon splits) */
    GLPGP_QFACE_PAVED = 2,    /* the repair's region mesher (quads grown from the region's boundary) */
    GLPGP_QFACE_FALLBACK = 3  /* the repair's last resort (triangles split into quads) */
};
#define GLPGP_QFACE_KINDS 4

/* One region the repair re-meshed (glpgp_quads_repair.region). */
typedef struct glpgp_quads_region {
    int faces_in;   /* faces removed (bad faces and their rings) */
    int quads_out;  /* quads made in their place */
    double sj_min;  /* smallest corner scaled Jacobian of the repaired quads in box in the
                     * repair's result (after its shape rounds, before the clean-up) */
    double x, y;    /* centroid of the quads made */
    double box[4];  /* their bounding box: xmin, ymin, xmax, ymax */
    int origin;     /* GLPGP_QFACE_PAVED or GLPGP_QFACE_FALLBACK: which mesher filled it */
    int round;      /* repair round (0-based; -1: the whole domain) */
} glpgp_quads_region;

/* Regions listed in a repair report: the ones with the lowest sj_min. */
#define GLPGP_QUADS_REGIONS_LISTED 48

/* What glpgp_quadmesh_repair did. */
typedef struct glpgp_quads_repair {
    int rounds;          /* repair rounds run (0: the mesh was valid) */
    int removed_faces;   /* faces removed (bad faces and their neighbours) */
    int regions;         /* regions re-meshed */
    int new_quads;       /* quads made in the regions */
    int snapped;         /* boundary vertices moved onto the domain boundary */
    int chord_strips;    /* grid lines added between boundary chords that cut off too much area */
    int paved_regions;   /* of the regions: filled by the region mesher */
    int fallback_regions;/* of the regions: filled by the fallback (triangles split into quads) */
    int whole_domain;    /* 0; 1: the local repair did not end valid and the whole domain was
                          * meshed again (region mesher, else the fallback); 2: the fallback of
                          * the input triangles themselves was needed */
    int flat_corners;    /* the last shape pass: flat boundary corners split (with two grid lines) */
    int sharp_tips;      /* the last shape pass: sharp tips re-meshed as their triangle's incircle kites */
    int shaped_vertices; /* the last shape pass: vertices moved to raise the worst corner near them */
    int nlisted;         /* entries of region[] (at most GLPGP_QUADS_REGIONS_LISTED) */
    glpgp_quads_region region[GLPGP_QUADS_REGIONS_LISTED];
} glpgp_quads_repair;

/* What glpgp_quadmesh_close_polygons and glpgp_quadmesh_smooth did. */
typedef struct glpgp_quads_closing {
    int closed_polygons;    /* odd faces (dislocation pentagons, ...) made quads */
    int strips_to_boundary; /* of the strips: those that end on the boundary (else: on a second odd face) */
    int strip_quads;        /* quads cut in two (or three, at a turn) along the strips */
    int strip_turns;        /* strip turns (each adds a valence 3 and a valence 5 vertex) */
    int split_even;         /* even polygons (hexagons, ...) split into quads */
    int smoothed_vertices;  /* vertices moved by the smoothing */
} glpgp_quads_closing;

/* What glpgp_quadmesh_cleanup did. */
typedef struct glpgp_quads_cleanup {
    int doublets;      /* interior valence-2 vertices removed (two quads merged) */
    int collapses;     /* quads removed by merging two opposite corners */
    int rotations;     /* edges rotated within the hexagon of their two quads */
    int passes;        /* passes over the mesh */
    int cost_before, cost_after; /* sum over vertices of d^2 + [d > 0], d = |valence - ideal| */
} glpgp_quads_cleanup;

/* A polygon mesh of a planar domain, mostly quads. Faces are counter-clockwise
 * and stored back to back: face f has the vertices
 * face_vert[face_start[f] .. face_start[f+1]). */
typedef struct glpgp_quadmesh {
    int nv;
    double *xy;         /* 2*nv (a surface's mesh: x and y of xyz) */
    int nf;
    int *face_start;    /* nf + 1 */
    int *face_vert;     /* face_start[nf] */
    unsigned char *face_origin; /* nf GLPGP_QFACE_* (NULL: every face from the grid, or unknown) */
    /* Extraction diagnostics (0 for meshes read from a file). */
    int singular_tris[2];     /* triangles skipped as singular for u / v (given by the result) */
    int inconsistent_tris[2]; /* triangles skipped because their chart did not close (rounding) */
    int collapsed_edges;      /* short edges contracted during the clean-up */
    int promoted_corners;     /* boundary vertices made face corners (3-gon -> quad) */
    int split_pentagons;      /* boundary pentagons split into two or three quads */
    int center_splits;        /* of those: three quads around a new center vertex */
    glpgp_quads_closing closing; /* set by glpgp_quadmesh_close_polygons / _smooth */
    glpgp_quads_repair repair;   /* set by glpgp_quadmesh_repair */
    glpgp_quads_cleanup cleanup; /* set by glpgp_quadmesh_cleanup */
    double *xyz;        /* 3*nv: a quad mesh of a 3D surface (faces counter-clockwise seen from
                         * the side the surface's normals point to); NULL in the plane */
} glpgp_quadmesh;

/* Extract the quad mesh of a result on mesh m (r->osc[k].z, .dirichlet and
 * .singular must match m; r->size is the target size h used by the clean-up
 * thresholds, <= 0: glpgp_default_size(m)). Faces that are not quads (near
 * unpaired singularities, or where the boundary cuts a cell) are kept as
 * polygons so the mesh covers the domain without gaps
 * (glpgp_quadmesh_close_polygons, or glpgp_quads_build, closes them). GLPGP_ERR_ARG on a
 * size mismatch, GLPGP_ERR_FORMAT when r has no oscillators, GLPGP_ERR_NUMERIC
 * when no face could be extracted. */
glpgp_status glpgp_quads_extract(const glpgp_mesh *m, const glpgp_result *r,
                                 glpgp_quadmesh **out);
void glpgp_quadmesh_destroy(glpgp_quadmesh **q);

/* Normal of face f of a 3D quad mesh (q->xyz), by Newell's formula: twice
 * the face's vector area, or of length 1 when unit (a zero vector stays 0). */
void glpgp_quadmesh_face_normal(const glpgp_quadmesh *q, int f, int unit, double *N);

/* All-quad refinement (one Catmull-Clark step without smoothing): every
 * face with n corners becomes n quads joined at its vertex centroid, each
 * edge is split at its midpoint (shared by both faces, so the result is
 * conforming). Quads give 4 quads, an n-gon n quads around a new valence-n
 * vertex, so the result has no non-quad face; the element size is halved
 * (edges about h / 2). Midpoints of boundary edges lie on the chord, within
 * the chord's sagitta of a curved domain boundary. The extraction
 * diagnostics are copied. GLPGP_ERR_ARG on an empty mesh. */
glpgp_status glpgp_quadmesh_subdivide(const glpgp_quadmesh *q, glpgp_quadmesh **out);

/* Make the faces that are not quads into quads, at the same element size.
 * Odd faces (a dislocation leaves a pentagon) are joined pairwise, or to
 * the boundary, through the shortest strip of quads between them: every
 * edge crossed gets its midpoint, the quads of the strip are cut in two
 * along it, and both ends become even polygons that are split into quads
 * (for a pentagon, through its T-junction vertex when possible, which leaves
 * no irregular vertex). Even polygons are split directly; triangles are
 * first merged with a neighbour, and so are the boundary quads whose
 * boundary corner is nearly flat (150-180 deg) once that corner is dropped. A face whose
 * strip would make a quad with a scaled Jacobian below 0.05 is kept (count:
 * quality report). The strip statistics are set in *out, the extraction
 * diagnostics copied. new_vertices (may be NULL): *new_vertices receives a
 * calloc'ed flag per vertex of *out, 1 for the vertices added here (free()).
 * The algorithm is described at the top of quads/close.c. */
glpgp_status glpgp_quadmesh_close_polygons(const glpgp_quadmesh *q, glpgp_quadmesh **out,
                                           unsigned char **new_vertices);

/* Quality-guarded smoothing: the interior vertices that are flagged in mark
 * (may be NULL), or belong to a face whose smallest corner scaled Jacobian
 * is below sj_below, and their edge neighbours, move 1/4, 1/2, 3/4 or all of
 * the way to the mean of their edge neighbours: the step that most raises
 * the worst corner of the faces around the vertex, and only if it raises it
 * by 1e-3 (so good regions keep the positions given by the
 * parametrization); at most `iterations` sweeps. Boundary vertices never
 * move. *moved (may be NULL): vertices that moved. */
glpgp_status glpgp_quadmesh_smooth(glpgp_quadmesh *q, const unsigned char *mark, int iterations,
                                   double sj_below, int *moved);

/* Local repair (quads/repair.c): the faces of q that are invalid against
 * the domain m (not quads, inverted, degenerate or flat, non-manifold,
 * pinched, overlapping, outside the domain, a boundary edge farther than
 * h/4 from the domain boundary, over a lost hole, corner or feature) are
 * removed with one ring of neighbours (more in later rounds, at most 4),
 * and each hole left is filled with quads: the polygon between the kept
 * faces and the domain boundary (input boundary vertices, corners kept) is
 * triangulated (constrained Delaunay, inner edges longer than
 * 2.6 h bisected) and every triangle becomes 3 or 5 convex quads without splitting
 * the edges shared with the kept faces. Boundary vertices within h/4 of the
 * domain boundary are first moved onto it. smooth: sweeps of
 * glpgp_quadmesh_smooth on the new vertices. keep_polygons: faces that are
 * not quads are not bad (--keep-polygons). q may have no face (the
 * extraction found none): the whole domain is meshed. *out: a new mesh (a copy when
 * nothing was wrong; still invalid when a region could not be filled: the
 * quality report tells). The algorithm is described at the top of
 * quads/repair.c. */
glpgp_status glpgp_quadmesh_repair(const glpgp_quadmesh *q, const glpgp_mesh *m, double h, int smooth,
                                   int keep_polygons, glpgp_quadmesh **out);

/* Topological clean-up of an all-quad mesh (quads/cleanup.c): doublet
 * removal, diagonal collapse and edge rotation, each applied only where it
 * lowers sum d^2 + [d > 0] over the vertices, d = |valence - ideal| (ideal:
 * 4 inside, round(boundary angle / 90 deg) + 1 on the boundary) and kept
 * only when the faces around it (after a local smoothing) keep a smallest
 * corner scaled Jacobian >= min(0.15, the smallest before) and > 0.05. Boundary vertices
 * never move nor go, so the boundary, corners and area are unchanged.
 * *out: the cleaned mesh (q's diagnostics, cleanup set), or NULL when q is
 * not all quads, is non-manifold or nothing could be improved (q stands). */
glpgp_status glpgp_quadmesh_cleanup(const glpgp_quadmesh *q, glpgp_quadmesh **out);

/* On a 3D surface (m->xyz): glpgp_quads_extract refuses it (GLPGP_ERR_ARG),
 * glpgp_quads_build runs glpgp_quads_build_surface and glpgp_quads_quality
 * (a surface's mesh against its surface) glpgp_quads_quality_surface. */

/* What glpgp_quads_build does after the extraction. */
typedef struct glpgp_quads_options {
    int keep_polygons;  /* 1: leave non-quad faces as they are (no strips) */
    int smooth;         /* smoothing sweeps (0: none; default 20) */
    double smooth_below;/* also smooth around faces with scaled Jacobian below this (default 0.5) */
    int all_quads;      /* 1: one Catmull-Clark step at the end (h halves) */
    int repair;         /* 1: glpgp_quadmesh_repair after the smoothing (default) */
    int cleanup;        /* 1: glpgp_quadmesh_cleanup after the repair (default) */
    double feature_angle; /* a surface's sharp edges the smoothing and the last resort keep
                           (degrees, glpgp_surface_features; default GLPGP_FEATURE_ANGLE_DEFAULT;
                           the CLI and Python pass the solve's --feature-angle) */
} glpgp_quads_options;

/* The defaults: strips on, 20 smoothing sweeps, smooth_below 0.5, repair on, clean-up on, no refinement,
 * feature_angle GLPGP_FEATURE_ANGLE_DEFAULT. */
void glpgp_quads_options_default(glpgp_quads_options *o);

/* The user-settable members of glpgp_quads_options, one descriptor each
 * (glpgp/optdesc.h; quads/options.c): --keep-polygons, --smooth,
 * --all-quads, --no-repair, --no-cleanup (group NULL: the command places
 * them). */
const glpgp_optdesc *glpgp_quads_option_table(void);

/* Extraction + closing of the polygons + smoothing + repair + clean-up
 * (glpgp_quadmesh_cleanup, its result kept only when it is as valid as the
 * mesh before and has no more irregular vertices) (+ refinement), as the
 * CLI does it. With repair on, an extraction that finds no face
 * (GLPGP_ERR_NUMERIC: the oscillators collapsed) is not an error: the
 * repair meshes the whole domain. *h: in: the target size, out: the size the mesh is made for
 * (halved by all_quads). o = NULL: the defaults. */
glpgp_status glpgp_quads_build(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                               glpgp_quadmesh **out, double *h);

#define GLPGP_QUADS_MAXVAL 8 /* valence histogram bins 0..MAXVAL (last: >= MAXVAL) */
/* The scaled Jacobian a finite-element user accepts (the repair's shape
 * rounds re-mesh quads below it that no sharp domain corner limits). */
#define GLPGP_QUADS_SJ_GOAL 0.3
/* A result whose repaired share is above this is flagged "mostly repaired". */
#define GLPGP_QUADS_MOSTLY_REPAIRED 0.5

/* What the surface pipeline did (glpgp_quads_build_surface; the report's
 * surface_steps). */
typedef struct glpgp_quads_surface_steps {
    int extracted_faces;   /* faces of the extraction (0: none) */
    int extracted_quads;   /* of those, quads */
    int closed;            /* faces made quads: two odd faces across a side joined, or an even
                              face, split into quads (up to 10 corners; a valid split only) */
    int strips;            /* odd faces joined pairwise through strips of quads cut in two */
    int subdivided;        /* 1: faces other than quads were left and every face was split
                              (Catmull-Clark, h/2) */
    int split_faces;       /* faces split locally: the bad ones and the quad strips through them
                              (Catmull-Clark in the bad regions, in two across the strips) */
    int refined_faces;     /* faces refined locally where the mesh was too far from the surface:
                              3 x 3 in the far faces, transition templates around them */
    int fallback;          /* 1: the extraction was not valid: the last resort, triangles split into
                              quads (coarse_triangles of a coarsened triangulation, else the input's) */
    int coarse_triangles;  /* the last resort's coarse triangles (0: the input's own) */
    unsigned invalid_before; /* GLPGP_QUADS_BAD_* of the extraction's mesh when it was not used */
    int local_regions;     /* regions of bad faces repaired locally (flattened, meshed by the cut
                              mesher, lifted onto the surface; the report's repair lists them) */
    int local_faces_in;    /* faces those regions removed */
    int local_quads_out;   /* quads made in their place */
    double local_sj_min;   /* their smallest scaled Jacobian (before the smoothing) */
    int smoothed;          /* vertices moved by the smoothing on the surface (o->smooth sweeps) */
    double sj_before;      /* smallest scaled Jacobian before the smoothing */
    double sj_after;       /* and after it (the same when it moved nothing or was undone) */
    int flat_corners;      /* flat boundary corners split like triangles (a boundary vertex in one
                              quad whose corner there is obtuse and below 0.3), kept when the mesh
                              stayed valid with a higher smallest scaled Jacobian */
    int flat_faces;        /* faces split for them (the quads and the strips through their sides) */
    double flat_sj_before, flat_sj_after; /* the smallest scaled Jacobian before and after that split */
    int parts;             /* connected components meshed apart (0: one); the path fields above
                              (subdivided, fallback, coarse_triangles) are the largest part's, the
                              counts the sums over the parts */
    int parts_last_resort; /* of them: ended in the last resort */
} glpgp_quads_surface_steps;


/* Quality report of a polygon mesh (see glpgp_quads_quality). */
typedef struct glpgp_quads_report {
    int vertices, faces, quads, others; /* others = faces with != 4 corners */
    int others_by_size[8];              /* 3, 4(unused), 5, ... 9+ corners: index n-3 capped at 7 (index 1 unused) */
    int valence_interior[GLPGP_QUADS_MAXVAL + 1];
    int valence_boundary[GLPGP_QUADS_MAXVAL + 1];
    int irregular_interior;  /* interior vertices with valence != 4 */
    int irregular_boundary;  /* boundary vertices with valence != ideal (from the boundary angle) */
    int irregular;           /* sum of both */
    double sj_min, sj_mean, sj_p01; /* scaled Jacobian of the quads (min over corners) */
    double sj_min_corner;    /* min over the quads of their scaled Jacobian over what the domain's
                              * sharp corners allow them (sin of the smallest interior angle
                              * below 90 degrees of a domain corner among their vertices, else 1):
                              * 1 = every quad as good as its corner allows */
    int below_sj_goal;       /* quads below GLPGP_QUADS_SJ_GOAL and below 0.9 of that bound */
    int quads_by_origin[GLPGP_QFACE_KINDS]; /* quads per face origin (all grid without origins) */
    double repaired_share;   /* share of the quads that the repair made (origins repair, fallback) */
    int inverted;            /* faces with area <= 0 or a quad corner with scaled Jacobian < 0 */
    int degenerate;          /* faces with a repeated vertex, a zero-length edge or ~zero area */
    int edges, boundary_edges, nonmanifold_edges; /* nonmanifold: edges used by > 2 faces */
    double len_mean, len_min, len_max; /* edge length / h */
    double area, domain_area; /* total face area; domain area (0 when no domain given) */
    double hausdorff;        /* max of the two one-sided distances below, in units of h
                              * (-1 when no domain given) */
    double dist_quad_to_domain, dist_domain_to_quad;
    double gap_edges;        /* boundary edges of the quad mesh farther than h/4 from the
                              * domain boundary (holes in the quad mesh); -1 without domain */
    double h;
    int singular[2];         /* singular triangles of the solve (u, v), -1 if unknown */
    glpgp_quads_closing closing; /* copied from the mesh (0 when it was not closed) */
    /* Validity (one orientation for the whole mesh: the sign of its total
     * signed area; inverted counts the faces of the other sign). */
    int orientation;         /* +1: faces counter-clockwise, -1: clockwise */
    int overlaps;            /* faces overlapping another face: an edge crossing another
                              * edge, or a vertex inside the face or on its sides */
    int pinched;             /* vertices whose faces form more than one edge-connected fan */
    int boundary_loops;      /* loops of boundary edges of the mesh */
    int domain_loops;        /* boundary loops of the domain (-1 without domain) */
    int outside;             /* faces with a corner outside the domain or an edge crossing
                              * its boundary (-1 without domain) */
    int far_faces;           /* faces with a boundary edge farther than h/4 from the domain
                              * boundary, or over a part of the domain boundary farther than
                              * h/4 from the mesh boundary (-1 without domain) */
    int corners_lost;        /* domain corners (boundary turn > 40 deg) without a mesh vertex
                              * (-1 without domain) */
    double area_ratio;       /* area / domain_area (-1 without domain) */
    double bnd_vertex_dist;  /* largest distance of a mesh boundary vertex from the domain
                              * boundary, in units of h (-1 without domain) */
    unsigned invalid;        /* GLPGP_QUADS_BAD_* bits: why the mesh is not valid (0: valid) */
    glpgp_quads_repair repair;/* copied from the mesh */
    glpgp_quads_cleanup cleanup; /* copied from the mesh */
    /* Irregular interior vertices against the singularities of the cross
     * field (glpgp_quads_quality_cross); all -1 when no cross field was
     * given (glpgp_quads_quality sets them so): the report then omits them. */
    int cross_singularities; /* cross-field singularities given */
    double cross_radius;     /* "near": within this distance (the solve's target size h) */
    int irregular_near_cross;/* irregular interior vertices within cross_radius of a singularity */
    int irregular_far_cross; /* the other irregular interior vertices (near + far = irregular_interior) */
    int cross_matched;       /* singularities with an irregular interior vertex within cross_radius */
    /* Surfaces (glpgp_quads_quality_surface; 0 in the plane): hausdorff,
     * the distances, area and loops are against the input surface. */
    int surface;             /* 1: a report of a surface's quad mesh */
    int euler, domain_euler; /* V - E + F of the quads and of the input surface */
    int has_steps;           /* 1: steps holds the surface pipeline's steps (set by the caller of
                                glpgp_quads_build_surface; JSON "surface": {"steps": ...}) */
    glpgp_quads_surface_steps steps;
} glpgp_quads_report;

/* Reasons a quad mesh is invalid (glpgp_quads_report.invalid). The domain
 * reasons are only tested when the report was made with a domain. */
enum {
    GLPGP_QUADS_BAD_INVERTED = 1u << 0,    /* inverted faces */
    GLPGP_QUADS_BAD_DEGENERATE = 1u << 1,  /* degenerate faces */
    GLPGP_QUADS_BAD_NONMANIFOLD = 1u << 2, /* non-manifold edges (or folds across an edge) */
    GLPGP_QUADS_BAD_NONQUAD = 1u << 3,     /* faces that are not quads */
    GLPGP_QUADS_BAD_PINCHED = 1u << 4,     /* pinched vertices */
    GLPGP_QUADS_BAD_OVERLAP = 1u << 5,     /* overlapping faces */
    GLPGP_QUADS_BAD_OUTSIDE = 1u << 6,     /* faces outside the domain */
    GLPGP_QUADS_BAD_LOOPS = 1u << 7,       /* boundary loops differ from the domain's (lost hole, gap) */
    GLPGP_QUADS_BAD_AREA = 1u << 8,        /* area off by more than 1% */
    GLPGP_QUADS_BAD_HAUSDORFF = 1u << 9,   /* boundary Hausdorff distance above h/4 */
    GLPGP_QUADS_BAD_GAPS = 1u << 10,       /* boundary edges away from the domain boundary */
    GLPGP_QUADS_BAD_CORNERS = 1u << 11,    /* domain corners without a mesh vertex */
    GLPGP_QUADS_BAD_EMPTY = 1u << 12,      /* no face */
    GLPGP_QUADS_BAD_TOPOLOGY = 1u << 13    /* surfaces: Euler characteristic differs from the input's */
};
#define GLPGP_QUADS_BAD_COUNT 14

/* Short name of reason bit b ("inverted", "non-quad", ...); NULL for an unknown bit. */
const char *glpgp_quads_bad_name(unsigned b);

/* Write the reasons of qq->invalid, less the bits in ignore, as one line
 * ("2 inverted faces, 1 lost hole (boundary loops 3 of 4)") into buf.
 * Returns the bits that remain (0: valid once ignore is taken out). */
unsigned glpgp_quads_invalid_text(const glpgp_quads_report *qq, unsigned ignore, char *buf, size_t n);

/* Compute the quality report of q for target size h (> 0). domain (may be
 * NULL) is the triangle mesh whose boundary the quads should reproduce: it
 * gives the Hausdorff distances and domain_area. Ideal boundary valence: a
 * boundary vertex whose quad-mesh interior angle is a is regular when its
 * valence is round(a / 90 deg) + 1 (3 on a straight boundary, 2 at a convex
 * right-angle corner). */
glpgp_status glpgp_quads_quality(const glpgp_quadmesh *q, const glpgp_mesh *domain, double h,
                                 glpgp_quads_report *out);

/* Count the irregular interior vertices of q (valence != 4, the vertices
 * not on a boundary edge; the same rule as glpgp_quads_quality) that lie
 * within distance radius (> 0; the solve's target size h) of one of the
 * nsing points sing (the cross-field singularities of a --field cross solve,
 * glpgp/cross.h; sing may be NULL when nsing is 0) and those that do not,
 * and the singularities that have an irregular interior vertex within
 * radius: fills qq->cross_* and qq->irregular_near_cross / _far_cross (qq
 * made by glpgp_quads_quality on the same q). GLPGP_ERR_ARG on radius <= 0,
 * nsing < 0 or an empty mesh. */
struct glpgp_cross_sing;
glpgp_status glpgp_quads_quality_cross(const glpgp_quadmesh *q, const struct glpgp_cross_sing *sing, int nsing,
                                       double radius, glpgp_quads_report *qq);

/* Print the report as a short human-readable block (each line prefixed). */
void glpgp_quads_print(FILE *f, const glpgp_quads_report *qq, const char *prefix);

/* Valence (number of distinct edges) of every vertex of q: *val is a
 * calloc'ed array of q->nv + 1 ints (free()). */
glpgp_status glpgp_quadmesh_valences(const glpgp_quadmesh *q, int **val);

/* Smallest corner scaled Jacobian of face f (1 for a rectangle; <= 0 at a
 * flat or reflex corner; -1 at a zero-length side). */
double glpgp_quadmesh_face_sj(const glpgp_quadmesh *q, int f);

/* ---- quad meshes of 3D surfaces (issue 29) ---------------------------- */

/* Extract the polygon mesh of a surface result (quads/extract_surface.c):
 * the integer level lines of the phases read per triangle through its
 * matching, traced across the triangles; positions in 3D (xyz set, xy
 * their x and y). Faces that are not quads are kept as polygons. Errors as
 * glpgp_quads_extract; GLPGP_ERR_ARG when m is not a surface. */
glpgp_status glpgp_quads_extract_surface(const glpgp_mesh *m, const glpgp_result *r, glpgp_quadmesh **out);

/* The last resort on a surface: every input triangle split into 3 quads
 * around its centroid through its sides' midpoints (valid by construction:
 * each quad is planar and convex in its triangle's plane; same topology).
 * A refined surface that keeps its input (m->surf->origin) splits the
 * input's triangles: the same surface (bisection's points lie on the input
 * triangles' sides) with a refinement's factor fewer quads. Faces of origin
 * GLPGP_QFACE_FALLBACK. */
glpgp_status glpgp_quads_surface_fallback(const glpgp_mesh *m, glpgp_quadmesh **out);

/* One Catmull-Clark split of every face in 3D (no smoothing): all quads,
 * edges about h / 2; origins kept. */
glpgp_status glpgp_quadmesh_subdivide_surface(const glpgp_quadmesh *q, glpgp_quadmesh **out);

/* The quality report of a surface's quad mesh against the surface m
 * (quads/check_surface.c): the planar report's counts, with the scaled
 * Jacobian in each face's best-fit plane, orientation against the
 * surface's normal, manifold edges and vertices, Euler characteristic and
 * boundary loops against m's, two-sided Hausdorff distance (<= h/4) and
 * area (within 2%). qq->surface = 1. */
glpgp_status glpgp_quads_quality_surface(const glpgp_quadmesh *q, const glpgp_mesh *m, double h,
                                         glpgp_quads_report *qq);

/* The relative area difference a surface's quad mesh may have (the
 * verdict's bound): 2% plus what flat faces of a curved surface lose,
 * 2 (d/h)^2 for quads whose corners are on the surface and whose faces
 * are within d (qq->dist_quad_to_domain h) of it (a flat face of
 * half-diagonal h/sqrt2 under a cap of depth d covers 1 - (d/rho)^2 of it). */
double glpgp_quads_surface_area_tolerance(const glpgp_quads_report *qq);

/* Smallest corner scaled Jacobian of face f of a surface's quad mesh, in
 * its best-fit (Newell) plane; -1 for a face without area or with a side
 * of about 1e-9 of its size or less (a corner there has no direction). */
double glpgp_quadmesh_face_sj_surface(const glpgp_quadmesh *q, int f);

/* Quality-guarded smoothing on the surface (quads/smooth_surface.c): sweeps
 * (at most `sweeps`) of tangential moves of the free vertices (not on the
 * quad mesh's boundary, not on the input's boundary or sharp features:
 * glpgp_surface_features at feature_deg) towards the mean of their edge neighbours or the corner that makes their
 * worst face a parallelogram, each moved back onto the surface and kept
 * only when the smallest scaled Jacobian of its faces rises and no face
 * falls below min(0.3, its value before) or turns over. *moved: vertices
 * moved at least once (may be NULL). */
glpgp_status glpgp_quads_smooth_surface(const glpgp_mesh *m, double h, double feature_deg, int sweeps,
                                        glpgp_quadmesh *q, int *moved);

/* The coarse last resort (quads/coarse_surface.c): m's triangles coarsened by
 * half-edge collapses to edges of about 2 h (boundaries, sharp features
 * and the topology kept, their curves' teeth cut within 0.1 h; new
 * triangles within 0.2 h of m, smallest angle 17 degrees unless one before
 * was smaller), free vertices relaxed along m between the passes, each
 * coarse triangle split into three quads. *ntri: the coarse triangles (may be NULL). The result is
 * not checked. Sharp features at GLPGP_FEATURE_ANGLE_DEFAULT
 * (glpgp_quads_build_surface passes glpgp_quads_options.feature_angle). */
glpgp_status glpgp_quads_surface_fallback_coarse(const glpgp_mesh *m, double h, glpgp_quadmesh **out, int *ntri);

/* What glpgp_quads_build_surface did. */

/* The surface pipeline (quads/quads_surface.c): extraction; two odd
 * faces that share a side (a triangle and a pentagon around a +1/4
 * singularity between grid points) joined, and the even faces, are split
 * into quads (the split with the best smallest scaled Jacobian, above
 * 0.05, up to 10 corners); when that is not valid, the local repair,
 * then the local split of the bad faces and their quad strips (see
 * docs/surfaces.md); when faces that
 * are not quads are left, one Catmull-Clark split (edges about h/2, the
 * new points moved onto the surface; skipped when o->keep_polygons); when
 * that is not valid (glpgp_quads_quality_surface against the target h: the
 * user's tolerance), the last resort (glpgp_quads_surface_fallback;
 * o->repair = 0: the extraction's mesh stands, invalid); then the
 * smoothing on the surface and the split of flat boundary corners (kept
 * when valid and better). A surface of several connected components is
 * meshed one component at a time (quads/components_surface.c): a part
 * that ends in the last resort does not take the others with it. *h: the
 * target size (unchanged). steps may be NULL. */
glpgp_status glpgp_quads_build_surface(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quads_options *o,
                                       glpgp_quadmesh **out, double *h, glpgp_quads_surface_steps *steps);

#ifdef __cplusplus
}
#endif

#endif
