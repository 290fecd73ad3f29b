/* glpgp/mesh.h: planar triangle meshes: creation with validation (planarity
 * is checked by the readers in glpgp/io.h, here: indices, degenerate
 * triangles, non-manifold edges, orientation), boundary loops and outward
 * boundary normals. Built-in shapes: glpgp/shapes.h. Triangulated surfaces
 * in 3D are glpgp_meshes too (xyz set, xy NULL): glpgp/surface.h. Layer: mesh. */
#ifndef GLPGP_MESH_H
#define GLPGP_MESH_H

#include "glpgp/status.h"

#include <limits.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One rank's part of a distributed mesh (glpgp_mesh.part; NULL: a whole
 * mesh). Its vertices are the rank's owned ones, local ids 0 .. nv_owned-1
 * (global ids first .. first + nv_owned - 1, increasing), then its ghosts
 * (one layer: every other vertex of a triangle touching an owned vertex,
 * increasing global id); its triangles are those touching an owned vertex
 * (whole-mesh order and orientation). The boundary flags and normals are the
 * whole mesh's (a cut between parts is no boundary), nloops is 0, and area,
 * bbox and mean_edge are the whole mesh's, so sizes and eps derived from
 * them are the same on every rank. Built on the rank that holds the whole
 * mesh (glpgp_mesh_extract_part) and sent to the others. */
typedef struct glpgp_mesh_part {
    int nv_owned;      /* owned vertices: local 0 .. nv_owned-1 */
    int first;         /* global id of local vertex 0 */
    int nv_global, nt_global;
    int *gid;          /* nv: global id of each local vertex */
    double *size;      /* 2 nv: local size of u then v (size[k nv + i]) from the whole mesh; NULL: uniform h */
    double center[2];  /* area centroid of the whole mesh (radial field's default center) */
    double size_opt;   /* glpgp_options.size of the rank that built the parts (0: default) */
} glpgp_mesh_part;

/* Whether local triangle t of a part is counted by its rank: its lowest
 * global vertex is owned (each triangle is counted by exactly one rank). */
static inline int glpgp_part_counts_tri(const glpgp_mesh_part *p, const int *tri, int t)
{
    int g = p->gid[tri[3 * t]];
    for (int a = 1; a < 3; a++)
        if (p->gid[tri[3 * t + a]] < g) g = p->gid[tri[3 * t + a]];
    return g >= p->first && g < p->first + p->nv_owned;
}

/* A boundary vertex where the boundary turns by more than this many degrees is
 * a domain corner: kept as a quad-mesh vertex by the extraction and the
 * repair, checked as one by the quality check, and not counted as curvature
 * by the size field's chord budget. One value for all of them. */
#define GLPGP_CORNER_DEG 40.0

struct glpgp_surface; /* glpgp/surface.h */

typedef struct glpgp_mesh {
    int nv;            /* vertices */
    int nt;            /* triangles */
    double *xy;        /* 2*nv coordinates (NULL for a surface) */
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
    glpgp_mesh_part *part; /* one rank's part of a distributed mesh (owned), NULL: a whole mesh */
    /* A triangulated surface in 3D (glpgp/surface.h; NULL for planar meshes):
     * 3*nv coordinates, its frames and connection (owned), and its 3D
     * bounding box xmin, ymin, zmin, xmax, ymax, zmax. */
    double *xyz;
    struct glpgp_surface *surf;
    double bbox3[6];
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

/* The largest mesh the library accepts (glpgp_mesh_create, glpgp_mesh_create_surface,
 * refinement): every int product of a count the library forms (up to 12 * nt
 * and 6 * nv: element-matrix entries, corner lists, coupled unknowns, device
 * buffers) stays below INT_MAX: about 179 million triangles, 358 million
 * vertices. */
#define GLPGP_MESH_MAX_TRIANGLES (INT_MAX / 12)
#define GLPGP_MESH_MAX_VERTICES (INT_MAX / 6)
/* GLPGP_ERR_LIMIT naming the count and the limit when nv or nt is over them. */
glpgp_status glpgp_mesh_check_size(long long nv, long long nt);
void glpgp_mesh_destroy(glpgp_mesh **m);
/* Free m's arrays (coordinates, triangles, boundary loops, flags, normals,
 * a part's ids and sizes), keeping its counts and scalars (nv, nt, nloops,
 * area, bbox, mean_edge, orientation_fixed) for reports: afterwards m may
 * only be read for those or destroyed. For a process that handed the mesh
 * on (rank 0 of a distributed run once the parts are sent). */
void glpgp_mesh_release_arrays(glpgp_mesh *m);

/* ---- partitions (mesh/partition.c) ---- */

/* part[i] <- the part (0 .. nparts-1) of vertex i, part p holding exactly
 * size[p] vertices (sizes sum to m->nv): recursive coordinate bisection,
 * each set split across the longer side of its bounding box. Deterministic
 * (ties broken by vertex index): every process computes the same parts. */
glpgp_status glpgp_mesh_partition(const glpgp_mesh *m, int nparts, const int *size, int *part);
/* Each vertex's triangles: *ptr (nv + 1) and *list (3 nt), vertex i's in
 * list[ptr[i] .. ptr[i + 1]) by increasing index; the caller frees both
 * (both NULL after a failure). */
glpgp_status glpgp_mesh_vertex_triangles(const glpgp_mesh *m, int **ptr, int **list);

/* new_of_old[i] <- the reverse Cuthill-McKee number of vertex i (a
 * permutation of 0 .. nv-1): breadth-first from a pseudo-peripheral vertex
 * of each connected component, neighbours by increasing degree (ties by
 * index), the whole order reversed. Neighbours then get nearby numbers
 * (small bandwidth): matrix rows gather their columns from a few cache
 * lines. Deterministic. */
glpgp_status glpgp_mesh_rcm_order(const glpgp_mesh *m, int *new_of_old);

/* Triangle shape: *min_angle the smallest corner angle of m in degrees,
 * *nslivers the triangles with a corner below sliver_deg degrees (CAD
 * exports triangulate a face as a fan of such slivers; P1 on them is
 * inaccurate and longest-edge refinement keeps them thin). */
void glpgp_mesh_angles(const glpgp_mesh *m, double sliver_deg, double *min_angle, int *nslivers);
/* *out <- m with vertex i renumbered new_of_old[i] (a permutation of
 * 0 .. nv-1); triangles keep their order and corner order. */
glpgp_status glpgp_mesh_renumber(const glpgp_mesh *m, const int *new_of_old, glpgp_mesh **out);
/* *out <- the part of rank q of the whole mesh m whose vertices are split
 * into P contiguous ranges, rank r owning [r nv / P, (r+1) nv / P) (the
 * numbering glpgp_mesh_renumber gives a partition): see glpgp_mesh_part.
 * size: 2 m->nv local sizes of the whole mesh (u then v) or NULL (uniform);
 * center, size_opt: copied into the part. */
glpgp_status glpgp_mesh_extract_part(const glpgp_mesh *m, int P, int q, const double *size, const double center[2],
                                     double size_opt, glpgp_mesh **out);
/* *out <- an empty part of nv local vertices and nt triangles: xy, tri,
 * on_boundary, normal_prev/next, part->gid (and part->size when sized)
 * allocated, no loops (nloops = 0), the rest zero; filled by
 * glpgp_mesh_extract_part or by a rank receiving its part. Free:
 * glpgp_mesh_destroy. */
glpgp_status glpgp_mesh_part_create(int nv, int nt, int sized, glpgp_mesh **out);

#ifdef __cplusplus
}
#endif

#endif
