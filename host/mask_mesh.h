/* mask_mesh.h: triangle meshes of polygon-with-holes domains through the
 * Gmsh C API (gmshc.h), and the whole "mask image -> glpgp mesh" pipeline
 * (read with OpenImageIO, contour.h, Gmsh, glpgp_mesh_create validation)
 * used by `glpgp mesh` and `glpgp solve MASK.png`. Builds without Gmsh get
 * GLPGP_ERR_UNSUPPORTED ("built without Gmsh"). */
#ifndef GLPGP_MASK_MESH_H
#define GLPGP_MASK_MESH_H

#include "contour.h"
#include "mesh.h"

typedef struct glpgp_mask_options {
    glpgp_contour_options contour; /* threshold, invert, specks, tolerance, pixel size */
    double mesh_size;  /* Gmsh's target size in physical units (<= 0: default); its
                          meshes have a mean edge of about 0.7 mesh_size */
    double quad_size;  /* the h the mesh is meant for (> 0 when known, e.g. solve --size);
                          the default mesh size is h / 8, with h = quad_size or, when
                          <= 0, the solver's default h = bounding-box diagonal / 20
                          (so mesh size = diagonal / 160) */
    int algorithm;     /* Gmsh Mesh.Algorithm: 6 frontal-Delaunay (default), 5 Delaunay,
                          1 MeshAdapt, 8 frontal-Delaunay for quads is not allowed */
} glpgp_mask_options;

void glpgp_mask_options_default(glpgp_mask_options *o);

/* What the pipeline found and did (for the CLI summary). */
typedef struct glpgp_mask_info {
    int width, height;    /* image size in pixels */
    int nouter, nholes;   /* boundary loops kept */
    int boundary_points;  /* polygon vertices handed to Gmsh */
    double polygon_area;  /* area enclosed by the polygons (physical units) */
    double mesh_size;     /* edge length used */
    double seconds_read, seconds_contour, seconds_mesh;
} glpgp_mask_info;

/* Whether this build has the Gmsh C API (1) or not (0). */
int glpgp_have_gmsh(void);

/* The default mesh size for polygons p and a quad size h (<= 0: bounding-box
 * diagonal / 20): h / 8. */
double glpgp_mask_default_mesh_size(const glpgp_polygons *p, double quad_size);

/* Mesh the polygons with Gmsh (geo kernel: points, lines, one curve loop per
 * polygon, one plane surface per outer loop with its holes; uniform size
 * mesh_size; Mesh.Algorithm algorithm, <= 0 for 6), then build the glpgp mesh
 * with glpgp_mesh_create (validated). Gmsh prints nothing (General.Terminal
 * = 0); every Gmsh error becomes GLPGP_ERR_MESH with Gmsh's last message. */
glpgp_status glpgp_mesh_polygons(const glpgp_polygons *p, double mesh_size, int algorithm,
                                 glpgp_mesh **out);

/* Read the mask image at path, extract its contours and mesh them (see the
 * option struct for the defaults). The Douglas-Peucker tolerance actually used
 * is max(o->contour.tolerance, mesh_size / 20 in pixels): the boundary needs
 * no detail finer than the mesh. info may be NULL. */
glpgp_status glpgp_mask_mesh(const char *path, const glpgp_mask_options *o, glpgp_mesh **out,
                             glpgp_mask_info *info);

#endif
