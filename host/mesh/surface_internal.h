/* mesh/surface_internal.h: what the surface files of the mesh layer share
 * (surface.c: validation and topology; surface_geom.c: frames and
 * connection; surface_shapes.c: built-in surfaces). */
#ifndef GLPGP_MESH_SURFACE_INTERNAL_H
#define GLPGP_MESH_SURFACE_INTERNAL_H

#include "glpgp/surface.h"

/* n <- (b - a) x (c - a) (twice the area times the unit normal). */
static inline void glpgp_tri_normal3(const double *a, const double *b, const double *c, double *n)
{
    const double u0 = b[0] - a[0], u1 = b[1] - a[1], u2 = b[2] - a[2];
    const double v0 = c[0] - a[0], v1 = c[1] - a[1], v2 = c[2] - a[2];
    n[0] = u1 * v2 - u2 * v1;
    n[1] = u2 * v0 - u0 * v2;
    n[2] = u0 * v1 - u1 * v0;
}

/* glpgp_mesh_create_surface with the degenerate-triangle test at
 * min_area_rel x the bounding-box diagonal^2 (the public one's: 1e-14; a
 * refinement's: 0, its triangles the bisections of validated ones, as thin
 * as their ancestors but smaller: area > 0 only). */
glpgp_status glpgp_mesh_create_surface_area(int nv, const double *xyz, int nt, const int *tri, double min_area_rel,
                                            glpgp_mesh **out);

/* The boundary loops of surface m from next[v] (the end of the boundary
 * half-edge leaving v, -1 when none): loop_start, loop_vertices,
 * on_boundary, nloops, in increasing order of each loop's first vertex. */
glpgp_status glpgp_surface_loops(glpgp_mesh *m, const int *next);

/* s->twin (allocated by the caller, 3 m->nt ints: the half-edge running
 * the same edge, -1 on the boundary) and s->nedges from m->tri; a third
 * triangle on an edge is GLPGP_ERR_MESH naming it. *samedir: the first
 * half-edge whose twin runs the same way (-1: none). */
glpgp_status glpgp_surface_twins(glpgp_mesh *m, glpgp_surface *s, int *samedir);

/* The breadth-first orientation walk of seed's component across the
 * twins: flip[t] (-1 unvisited on entry) 1 when t runs against the seed;
 * queue[0, *n) its triangles, *closed whether it has no boundary edge.
 * Returns -1, or a half-edge whose two triangles cannot agree (a
 * non-orientable component: the walk stops there). */
int glpgp_surface_walk(const int *tri, const int *twin, int seed, signed char *flip, int *queue, int *n, int *closed);

/* The geometry of m->surf (normals, frames, angles, local coordinates,
 * rotations, connection, holonomy, dihedral angles) and m->mean_edge, from
 * the validated topology (twin, vstart). */
glpgp_status glpgp_surface_geometry(glpgp_mesh *m);

#endif
