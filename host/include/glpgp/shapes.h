/* glpgp/shapes.h: the built-in domains (square, disk, annulus, L-shape)
 * meshed at a requested vertex count, used by `shape:NAME[:N]` inputs, tests
 * and benchmarks. Layer: mesh. */
#ifndef GLPGP_SHAPES_H
#define GLPGP_SHAPES_H

#include "glpgp/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Default vertex count of a shape input without :N. */
#define GLPGP_SHAPE_DEFAULT_VERTICES 20000L
/* Range of N accepted by shape inputs. */
#define GLPGP_SHAPE_MIN_VERTICES 16L
#define GLPGP_SHAPE_MAX_VERTICES 100000000L

/* Built-in shapes at about `nverts` vertices (>= 16):
 *   "square"  unit square [0,1]^2
 *   "disk"    unit disk centered at the origin
 *   "annulus" radii 0.3 and 1.0 centered at the origin
 *   "lshape"  [0,1]^2 minus [0.5,1]^2
 * Triangles are well shaped (min angle >= 25 degrees). Deterministic.
 * Surfaces (glpgp_surface_generate, glpgp/surface.h): "sphere", "torus",
 * "genus2", "cube", "hemisphere", "halfcyl", and "halfcyl_flat" (planar). */
glpgp_status glpgp_mesh_generate(const char *shape, long nverts, glpgp_mesh **out);
/* NULL-terminated list of shape names, for help texts. */
const char *const *glpgp_mesh_shapes(void);
/* Whether name is a built-in shape. */
int glpgp_shape_known(const char *name);

/* Parse "shape:NAME[:N]" (the "shape:" prefix optional when allow_bare):
 * name (at most namelen - 1 characters) and N (default
 * GLPGP_SHAPE_DEFAULT_VERTICES). GLPGP_ERR_ARG with a message naming the
 * problem (malformed, unknown shape with the list of shapes, N out of range). */
glpgp_status glpgp_shape_parse(const char *spec, int allow_bare, char *name, size_t namelen,
                               long *nverts);

#ifdef __cplusplus
}
#endif

#endif
