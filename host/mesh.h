/* mesh.h: planar triangle meshes: creation with validation (planarity is
 * checked by the readers, here: indices, degenerate triangles, non-manifold
 * edges, orientation), boundary loops and outward boundary normals, readers
 * (OBJ, Gmsh MSH 2.2/4.1 ASCII), writers (OBJ, MSH 4.1), and the built-in
 * shape generator used by tests and benchmarks. */
#ifndef GLPGP_MESH_H
#define GLPGP_MESH_H

#include "status.h"

typedef struct glpgp_mesh {
    int nv;            /* vertices */
    int nt;            /* triangles */
    double *xy;        /* 2*nv coordinates */
    int *tri;          /* 3*nt vertex indices, every triangle counter-clockwise */

    /* Boundary (derived by glpgp_mesh_create). Loops are stored back to back in
     * loop_vertices; loop l is loop_vertices[loop_start[l] .. loop_start[l+1]),
     * ordered so the domain lies on the left (outer loop CCW, holes CW). Loop 0
     * is the outer loop (largest |signed area|). */
    int nloops;
    int *loop_start;    /* nloops + 1 */
    int *loop_vertices; /* loop_start[nloops] entries */
    unsigned char *on_boundary; /* nv flags */
    /* Per boundary vertex: outward unit normals of the boundary edge before
     * (prev) and after (next) the vertex along its loop; zero for interior
     * vertices. edge_normal_prev/next each hold 2*nv doubles. */
    double *normal_prev;
    double *normal_next;

    double area;        /* total area */
    double bbox[4];     /* xmin, ymin, xmax, ymax */
    double mean_edge;   /* mean edge length */
    int orientation_fixed; /* number of triangles flipped to make the mesh consistently CCW */
} glpgp_mesh;

/* Build a mesh from raw arrays (copied). Validates and normalises:
 *  - nv >= 3, nt >= 1, indices in range, no repeated vertex in a triangle;
 *  - no zero-area triangle (|area| <= 1e-14 * bbox diagonal^2) -> GLPGP_ERR_MESH;
 *  - no edge shared by more than two triangles (non-manifold) -> GLPGP_ERR_MESH;
 *  - orientation: each connected component is made consistent (triangles
 *    flipped, counted in orientation_fixed) and then counter-clockwise;
 *    a non-orientable configuration is rejected;
 *  - vertices used by no triangle are rejected (they would have no equation);
 *  - boundary vertices where the boundary is not a simple loop (pinched,
 *    two boundary loops touching) -> GLPGP_ERR_MESH.
 * Messages name the offending triangle/edge/vertex (0-based). */
glpgp_status glpgp_mesh_create(int nv, const double *xy, int nt, const int *tri, glpgp_mesh **out);
void glpgp_mesh_destroy(glpgp_mesh **m);

/* Read by extension: .obj or .msh (MSH 2.2 and 4.1 ASCII, 3-node triangles only).
 * Rejects: missing/unreadable file (GLPGP_ERR_IO), malformed content
 * (GLPGP_ERR_FORMAT), no triangles, non-planar input (z not constant, relative
 * tolerance 1e-9 of the bbox size) and everything glpgp_mesh_create rejects
 * (GLPGP_ERR_MESH). OBJ: `v x y [z]`, `f` with a, a/b, a//c, a/b/c forms and
 * negative (relative) indices; polygons with more than 3 corners are
 * fan-triangulated. Unused vertices are dropped silently (with renumbering). */
glpgp_status glpgp_mesh_read(const char *path, glpgp_mesh **out);

/* Write the triangles as OBJ or MSH 4.1 (by extension), atomically
 * (temporary file + rename). */
glpgp_status glpgp_mesh_write(const glpgp_mesh *m, const char *path);

/* Built-in shapes at about `nverts` vertices (>= 16):
 *   "square"  unit square [0,1]^2
 *   "disk"    unit disk centred at the origin
 *   "annulus" radii 0.3 and 1.0 centred at the origin
 *   "lshape"  [0,1]^2 minus [0.5,1]^2
 * Triangles are well shaped (min angle >= 25 degrees). Deterministic. */
glpgp_status glpgp_mesh_generate(const char *shape, long nverts, glpgp_mesh **out);
/* NULL-terminated list of shape names, for help texts. */
const char *const *glpgp_mesh_shapes(void);

#endif
