/* glpgp/surface.h: triangulated surfaces in 3D (issue 28): creation with
 * validation as an oriented 2-manifold with or without boundary, topology
 * (Euler characteristic, genus, boundary loops), and the discrete
 * differential geometry the surface solve needs: per-vertex tangent frames,
 * each triangle's own plane ("unfolded" corner coordinates), the rotation
 * from a vertex's frame into each of its triangles' frames, the discrete
 * Levi-Civita connection per half-edge and the holonomy per triangle.
 * Derivations: host/README.md "Surfaces". Layer: mesh.
 *
 * A surface is a glpgp_mesh with xyz set (3 nv coordinates) and xy NULL;
 * planar meshes have xyz NULL and none of this. Its boundary loops
 * (nloops, loop_start, loop_vertices, on_boundary) are set as for a planar
 * mesh, each loop walked with the surface on its left (seen from the side
 * the normals point to); normal_prev / normal_next are NULL.
 *
 * Angles. Vertex i's tangent plane is modelled by its fan of corners: the
 * corner angles alpha around i, in counter-clockwise order (about the
 * normal), starting at a reference edge (the first corner's outgoing edge;
 * on the boundary, the outgoing boundary edge), scaled by s_i = 2 pi /
 * Theta_i at an interior vertex (Theta_i = sum of its corner angles: the
 * cone is flattened to a plane) and s_i = 1 at a boundary vertex (its fan
 * unfolded as it is, so boundary corners keep their angle, as in the
 * plane). The direction of the half-edge i -> j has the angle theta_i(j) in
 * i's frame (Knoeppel, Crane, Pinkall, Schroeder 2013). A tangent vector at
 * i is the complex number of its angle in that frame.
 *  - connection of half-edge h = (i -> j): rho_h = theta_j(i) + pi -
 *    theta_i(j): a vector of angle a at i transported to j has angle
 *    a + rho_h (the angle to the edge is kept);
 *  - holonomy of triangle t: Omega_t = sum over its corners of
 *    alpha_{t,v} (s_v - 1), congruent to the sum of rho over its three
 *    half-edges mod 2 pi; sum over all triangles = sum over interior
 *    vertices of (2 pi - Theta_v) = 2 pi chi - sum over boundary vertices
 *    of (pi - Theta_v) (discrete Gauss-Bonnet, exact);
 *  - rotation of corner (t, a): phi_{t,a} maps an angle in vertex
 *    tri[3t+a]'s frame to triangle t's frame (the plane of txy): through
 *    the corner's outgoing edge it is beta_out - theta_out, through its
 *    incoming edge beta_in - theta_in; the two differ by alpha (1 - s_v)
 *    (0 on a developable surface) and phi is their mean. */
#ifndef GLPGP_SURFACE_H
#define GLPGP_SURFACE_H

#include "glpgp/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Dihedral angle (degrees) above which an interior edge is a sharp feature
 * (glpgp_options.feature_angle's default). */
#define GLPGP_FEATURE_ANGLE_DEFAULT 35.0

typedef struct glpgp_surface {
    int nv, nt;
    int nedges;         /* undirected edges */
    int ncomponents;    /* connected components */
    int euler;          /* chi = V - E + F */
    int genus;          /* sum over components of (2 - chi_c - b_c) / 2 */
    /* half-edge h = 3t + a runs from tri[3t+a] to tri[3t+(a+1)%3] */
    int *twin;          /* 3 nt: the opposite half-edge, -1 on the boundary */
    /* per vertex */
    int *vstart;        /* nv: the first corner of its fan (counter-clockwise; on the boundary
                           the corner whose outgoing half-edge is a boundary edge); the next
                           corner is the twin of the current one's incoming half-edge */
    double *vnormal;    /* 3 nv: unit normal (angle-weighted mean of its triangles') */
    double *vtangent;   /* 3 nv: the frame's first axis e_i: its reference edge projected
                           into the plane normal to vnormal, unit (f_i = n_i x e_i) */
    double *angle_sum;  /* nv: Theta_i */
    double *scale;      /* nv: s_i (2 pi / Theta_i inside, 1 on the boundary) */
    /* per corner c = 3t + a (vertex tri[c]) */
    double *corner;     /* 3 nt: the corner angle alpha */
    double *eangle;     /* 3 nt: theta of the corner's outgoing half-edge c in its vertex's frame */
    double *rot;        /* 3 nt: phi: vertex frame -> triangle frame (see the top) */
    /* per half-edge */
    double *conn;       /* 3 nt: rho_h */
    double *dihedral;   /* 3 nt: angle between the normals of the edge's two triangles
                           (radians, in [0, pi]; 0 on the boundary) */
    /* per triangle */
    double *txy;        /* 6 nt: corner a of t at (txy[6t+2a], txy[6t+2a+1]) in t's plane:
                           corner 0 at the origin, corner 1 on the positive x axis,
                           corner 2 above it (counter-clockwise) */
    double *tframe;     /* 9 nt: the plane's x axis, y axis and normal (3D unit vectors) */
    double *holonomy;   /* nt: Omega_t */
    /* where a refinement's triangles lie on the mesh it was refined from
     * (glpgp_mesh_refine_surface and _sized set otri and obary; NULL
     * elsewhere): the input triangle holding triangle t, and the barycentric
     * coordinates of t's corner a in it at obary[9t + 3a + k] (k: the input
     * triangle's corner). origin: that input mesh itself (owned), where
     * glpgp_surface_keep_origin kept it (the solve keeps it for a cross
     * field: its curvature term reads the input's normals, and where
     * origin_cross is set the cross field is solved there). */
    int *otri;          /* nt */
    double *obary;      /* 9 nt */
    struct glpgp_mesh *origin;
    int origin_cross;
} glpgp_surface;

/* Build a surface mesh from raw arrays (copied): xyz (3 nv), tri (3 nt).
 * Rejected with GLPGP_ERR_MESH and one line naming where:
 *  - fewer than 3 vertices or 1 triangle, an index out of range, a
 *    repeated vertex in a triangle, a non-finite coordinate, a vertex used
 *    by no triangle;
 *  - a degenerate triangle (area <= 1e-14 x the bounding-box diagonal^2);
 *  - a non-manifold edge (three or more triangles) or vertex (its corners
 *    form more than one fan: two sheets or cones touching at it);
 *  - inconsistent orientation (two triangles traverse their shared edge in
 *    the same direction; the surface is orientable: flip one of them), or a
 *    non-orientable surface (Moebius strip: no consistent orientation).
 * Then the topology (loops, Euler characteristic, genus) and the geometry
 * of glpgp_surface (m->surf). m->area, mean_edge are 3D; bbox holds the x,
 * y range and bbox3 the 3D box. */
glpgp_status glpgp_mesh_create_surface(int nv, const double *xyz, int nt, const int *tri, glpgp_mesh **out);

/* What glpgp_surface_fix changed. */
typedef struct glpgp_surface_fixes {
    int degenerate; /* zero-area triangles flipped away, dropped or collapsed */
    int flipped;    /* triangles reversed to orient their component alike */
    int pinched;    /* vertices whose triangles formed more than one fan */
    int added;      /* the vertices added for them (one per fan after the first) */
    int nonmanifold; /* edges of more than two triangles separated (bodies touching along an edge) */
    int nonmanifold_added; /* the vertices added for them */
    int duplicate;  /* triangles dropped that repeat another's three vertices (either way round) */
    int thin;       /* triangles of an angle below 1e-6 radians (not zero area) flipped away, dropped or
                       collapsed */
} glpgp_surface_fixes;

/* The repairs a surface from a file may need before
 * glpgp_mesh_create_surface (which stays strict), in place (mesh/surface_fix.c):
 *  - a triangle on the same three vertices as one before it (either way
 *    round: a face written twice) dropped (*nt shrinks, the order kept);
 *  - a zero-area triangle (the validation's test) removed: a cap (a vertex
 *    inside the opposite edge, a T-junction's filler) by flipping that
 *    edge with its neighbour (dropped on the boundary), a needle (two
 *    vertices nearly one) by collapsing them (*nt, *nv shrink: the
 *    triangles and vertices are compacted), and the pillows the collapses
 *    fold (two triangles on the same three vertices: a flat bubble or
 *    debris that encloses nothing) dropped;
 *  - then a triangle with an angle below 1e-6 radians the same way (two
 *    vertices a hair apart, as marching cubes leaves them: the P1 stiffness
 *    of the edge opposite is 1e6 and more, which stalls the linear
 *    solves), where a collapse keeps the surface manifold
 *    and turns no triangle over and a flip makes no edge twice; the
 *    surface moves by 1e-6 times the triangle's longest edge at most;
 *  - each connected component's triangles oriented alike; a component
 *    that needed flips is oriented outward when closed, else as most of
 *    its triangles were;
 *  - a pinched vertex (its triangles form several fans: sheets or cones
 *    touching at a point) split into one vertex per fan, the copies
 *    appended: *xyz (3 *nv doubles from glpgp_malloc) grows, *nv with it;
 *  - an edge of four or more triangles (bodies touching along an edge)
 *    separated: the triangles paired about the edge by angle, each pair
 *    behind both normals (a body's inside), and the edge's vertices split
 *    as pinched ones (needs the triangles to alternate in direction around
 *    the edge).
 * An input these repairs are not defined on (an index out of range, a
 * repeated vertex, an edge of three triangles or of more that do not
 * alternate, a non-orientable component) is left as it is for
 * glpgp_mesh_create_surface to name. */
glpgp_status glpgp_surface_fix(int *nv, double **xyz, int *nt, int *tri, glpgp_surface_fixes *fx);

/* *out: surface m with every triangle split in four at its edge midpoints
 * (mesh/subdivide.c): the same piecewise linear surface, sharp edges,
 * boundary loops and topology, edges halved; 4 nt triangles. */
glpgp_status glpgp_mesh_subdivide_surface(const glpgp_mesh *m, glpgp_mesh **out);

/* The longest edge of mesh m (its x, y, z; mesh/refine_surface.c). */
double glpgp_mesh_longest_edge(const glpgp_mesh *m);

/* What glpgp_mesh_refine_surface did. */
typedef struct glpgp_surface_refine_info {
    long splits;                /* edges bisected (= vertices added) */
    int nv0, nt0, nv, nt;       /* before and after */
    double max_edge0, max_edge; /* the longest edge before and after */
    double ratio0, ratio;       /* the largest edge / its target before and after (<= 1: reached) */
    double min_target;          /* the smallest target (per vertex: over the input's vertices) */
    int stopped;                /* 1: max_triangles reached before the target (ratio > 1) */
    int passes;                 /* refinements done (the solver's refinement to the local size may
                                   take several, the size recomputed on each refined mesh) */
} glpgp_surface_refine_info;

/* *out: surface m with every edge longer than target split, by conforming
 * longest-edge (LEPP) bisection (mesh/refine_surface.c): no edge longer
 * than target, edges already shorter left alone where no longer edge needs
 * them split; every new point the midpoint of an edge, so on an old edge
 * or inside an old triangle (the same piecewise linear surface, sharp
 * edges, boundary loops and topology), orientation kept, the smallest angle at least half the input's. *out NULL
 * when no edge is longer than target (or the first level already passes
 * max_triangles). With max_triangles > 0 the result has at most that many
 * triangles: the refinement goes in levels (longest edge down by sqrt 2
 * each) and keeps the last level within it (info->stopped). info may be
 * NULL. */
glpgp_status glpgp_mesh_refine_surface(const glpgp_mesh *m, double target, double max_triangles, glpgp_mesh **out,
                                       glpgp_surface_refine_info *info);

/* glpgp_mesh_refine_surface with a target per vertex (target: m->nv, each
 * positive and finite, else GLPGP_ERR_ARG): an edge is split while longer
 * than the smaller of its two ends' targets, a new vertex (an edge's
 * midpoint) gets the mean of that edge's ends' targets (the target
 * interpolated linearly). Where every edge already meets its target the
 * triangles are left as they are unless a longer edge's propagation path
 * passes through them. The levels, max_triangles and info as there (the
 * level k: edges longer than target x sqrt 2^k; info->ratio the largest edge
 * / target left, min_target the smallest input target). A uniform target
 * gives glpgp_mesh_refine_surface's mesh. */
glpgp_status glpgp_mesh_refine_surface_sized(const glpgp_mesh *m, const double *target, double max_triangles,
                                             glpgp_mesh **out, glpgp_surface_refine_info *info);

/* fine (refined from mid by glpgp_mesh_refine_surface*) refined from an
 * earlier mesh in turn (mid's otri and obary set): fine's otri and obary
 * made relative to that earlier mesh (the barycentric coordinates composed
 * through mid's triangles). Nothing to do where either has none. */
void glpgp_surface_origin_compose(glpgp_mesh *fine, const glpgp_mesh *mid);

/* Keep a copy of the input `coarse` in refined's surface (origin), which
 * must hold the triangles' origin in it (otri, obary): GLPGP_ERR_ARG
 * without. The copy is built from coarse's vertices and triangles (the
 * same frames and connection); origin_cross is set (the solve clears it
 * where the input is too coarse for the cross field's continuation). */
glpgp_status glpgp_surface_keep_origin(glpgp_mesh *refined, const glpgp_mesh *coarse);

/* Free a surface's arrays (NULL-safe, sets *s = NULL); glpgp_mesh_destroy
 * calls it. */
void glpgp_surface_destroy(struct glpgp_surface **s);

/* Whether m is a surface (xyz set). */
static inline int glpgp_mesh_is_surface(const glpgp_mesh *m) { return m && m->xyz != NULL; }

/* Length of the bounding-box diagonal (3D for a surface). */
double glpgp_mesh_diagonal(const glpgp_mesh *m);

/* The 3D unit vector of the tangent vector (c, s) (cos, sin of its angle)
 * in vertex i's frame: in the corner of i whose fan sector [theta, theta +
 * s_i alpha) holds the angle psi, the direction of its outgoing edge turned
 * by (psi - theta) / s_i in its triangle's plane (continuous in the angle,
 * an edge's direction at an edge's angle; outside a boundary vertex's fan
 * the nearer sector edge's). out: 3 doubles. */
void glpgp_surface_vertex_vector(const glpgp_mesh *m, int i, double c, double s, double *out);

/* Angle in vertex i's frame of the 3D vector v (projected into the tangent
 * plane; the inverse of glpgp_surface_vertex_vector up to rounding).
 * 0 when v is normal to the surface. */
double glpgp_surface_vertex_angle(const glpgp_mesh *m, int i, const double *v);

/* Feature half-edges: flag[h] = 1 on an interior edge whose dihedral angle
 * exceeds feature_deg degrees and that is a crease, not a scan's noise
 * (mesh/surface_geom.c): it separates its two triangles locally (no walk
 * of triangles within 2.5 of its neighbouring edge lengths joins them
 * without crossing another such edge), its sides' mean normals at that
 * scale still differ by 0.8 feature_deg and, unless it is sharper than 70
 * degrees, by twice either side's own normal spread (a faceted curved
 * surface's kinks are not creases), and its crease has 3 edges or
 * more or reaches the boundary. Both half-edges of it; boundary half-edges
 * 0. A refined surface that kept its input (origin) takes the input's
 * features. *count (may be NULL): the undirected feature edges. flag: 3 nt. */
glpgp_status glpgp_surface_features(const glpgp_mesh *m, double feature_deg, unsigned char *flag, int *count);

/* The interior edges whose dihedral angle exceeds feature_deg degrees (the
 * candidates of glpgp_surface_features, crease or not). */
int glpgp_surface_edges_above(const glpgp_mesh *m, double feature_deg);

/* What glpgp_surface_denoise did. */
typedef struct glpgp_surface_denoise_info {
    int noise_edges;       /* interior edges above the feature angle that are not creases, before */
    int noise_edges_after; /* and after */
    int folds, folds_after; /* triangles turned over against their neighbours, before and after */
    int rounds;            /* smoothing rounds kept (0: none) */
    int moved;             /* vertices that moved */
    int capped;            /* of them, those held at max_move */
    double max_move, mean_move; /* their displacement */
    double defect_rms, defect_rms_after; /* glpgp_surface_defect_rms before and after */
} glpgp_surface_denoise_info;

/* *out: surface m with its scan noise smoothed away (mesh/surface_denoise.c),
 * or NULL when m shows none (no interior edge above feature_deg that is not
 * a crease, no triangle turned over against its neighbours: a clean mesh
 * is left as it is). Where such edges and folds are, their vertices and
 * eight edge rings around them are smoothed by bilateral normal filtering
 * (the triangles' normals averaged with a range weight that keeps creases
 * and corners sharp, the vertices fitted to them; a fold's vertices also
 * relaxed); boundary vertices stay; no vertex moves more than max_move
 * (> 0). The same vertices and triangles (so the same topology); where
 * the smoothing would make a triangle degenerate, *out is NULL (the input
 * as it is). info: required. */
glpgp_status glpgp_surface_denoise(const glpgp_mesh *m, double feature_deg, double max_move, glpgp_mesh **out,
                                   glpgp_surface_denoise_info *info);

/* The root mean square angle defect 2 pi - Theta_v over the interior
 * vertices (radians; 0 without one): the spread of the discrete Gauss
 * curvature, which a scan's noise inflates (a smooth mesh of a closed
 * surface: about 4 pi (1 - g) / nv each). */
double glpgp_surface_defect_rms(const glpgp_mesh *m);

/* The sum over triangles of the holonomy (2 pi chi minus the boundary's
 * turning sum(pi - Theta_v) over the boundary vertices; 4 pi on a sphere). */
double glpgp_surface_total_holonomy(const glpgp_mesh *m);

/* Surface shapes at about nverts vertices, deterministic (glpgp/shapes.h
 * lists them with the planar ones): "sphere" (radius 1), "torus" (radii 1,
 * 0.4), "genus2" (a closed surface of genus 2), "cube" (edge 1, sharp
 * edges), "hemisphere" (open, radius 1), "halfcyl" (a rectangle of 2 pi x
 * 2 rolled up into half a cylinder of radius 2: developable; its vertex
 * columns lie on the cylinder's generators, so every strip between two is
 * planar and the polyhedral surface is isometric to "halfcyl_flat"),
 * "halfcyl_flat" (that polyhedron unrolled into the plane z = 0: the same
 * triangles, a planar mesh). */
glpgp_status glpgp_surface_generate(const char *shape, long nverts, glpgp_mesh **out);
/* Whether name is a surface shape (including the planar twin halfcyl_flat). */
int glpgp_surface_shape_known(const char *name);

#ifdef __cplusplus
}
#endif

#endif
