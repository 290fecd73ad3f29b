/* image/render3d_impl.h: the camera, z-buffer and overlays of the surface
 * pictures (render3d.c), shared with the 3D quad mesh's picture
 * (render3d_quads.c). Internal to the image layer. */
#ifndef GLPGP_RENDER3D_IMPL_H
#define GLPGP_RENDER3D_IMPL_H

#include "glpgp/image.h"
#include "glpgp/mesh.h"

typedef struct cam3 {
    double right[3], up[3], dir[3]; /* dir: from the surface towards the camera */
    double scale, ox, oy;           /* sample = (p . right - ox) scale, (oy - p . up) scale */
    int W, H;                       /* samples */
    int ss;                         /* samples per pixel side */
} cam3;

/* G-buffer: per sample the nearest triangle (-1: none), its barycentrics, depth. */
typedef struct gbuf {
    int *tri;
    float *l1, *l2;
    double *depth;
} gbuf;

/* An orthographic camera from o's azimuth and elevation fitted to m's
 * points (m->nv, m->xyz) with margin pixels around. */
void glpgp_r3_cam_setup(const glpgp_mesh *m, const glpgp_render_options *o, int margin, cam3 *c);
/* p in samples (x, y) and depth (larger: nearer). */
void glpgp_r3_project(const cam3 *c, const double *p, double *q);
/* m's triangles (m->nt, m->tri, m->xyz) into g (nearest per sample). */
void glpgp_r3_raster(const glpgp_mesh *m, const cam3 *c, gbuf *g);
/* Frees the buffers of g (not g itself). */
void glpgp_r3_gbuf_free(gbuf *g);
/* Whether point p is in front of what the samples around it show (q: projected). */
int glpgp_r3_visible(const cam3 *c, const gbuf *g, const double *p, double tol, double *q);
/* A filled anti-aliased disc of radius rad pixels at pixel (x, y). */
void glpgp_r3_disc(glpgp_image *im, double x, double y, double rad, const float *col);

/* Panels side by side with two caption lines each (render.c). */
glpgp_status glpgp_r_compose_panels(glpgp_image *const *panel, int n, const char *const *l1, const char *const *l2,
                                    const glpgp_render_options *o, glpgp_image **out);
/* A surface's figure (render3d_quads.c; glpgp_render_figure1 on a surface):
 * the input triangles shaded, the grid texture, the quad mesh q (NULL:
 * left out), each from o's view, with captions. */
glpgp_status glpgp_r_figure_surface(const glpgp_mesh *m, const glpgp_result *r, const glpgp_quadmesh *q,
                                    const glpgp_render_options *o, glpgp_image **out);

#endif
