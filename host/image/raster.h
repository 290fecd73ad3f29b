/* image/raster.h: the rasteriser's small pieces shared by the pictures of
 * the image layer (render.c: results in the plane, render3d.c: surfaces,
 * render_quads.c: quad meshes): straight-alpha compositing, anti-aliased
 * segments into a coverage buffer, the options' defaults and size check.
 * Private to host/image/ (raster.c). */
#ifndef GLPGP_IMAGE_RASTER_H
#define GLPGP_IMAGE_RASTER_H

#include "glpgp/image.h"

static inline double glpgp_clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

/* Composite colour c with coverage a over pixel p (straight RGBA). */
void glpgp_px_over(float *p, const float c[3], double a);

/* Anti-aliased round-capped stroke of segment a-b (pixel coordinates) into
 * the W x H coverage buffer cov (the max of the coverages). */
void glpgp_cov_stroke(float *cov, int W, int H, double ax, double ay, double bx, double by, double width);

/* Composite colour c over im where cov > 0, clearing cov. */
void glpgp_cov_apply(glpgp_image *im, float *cov, const float c[3]);

/* *o <- *opt (or the defaults when opt is NULL); GLPGP_ERR_ARG when its size
 * is outside [16, 32768]. */
glpgp_status glpgp_render_options_take(const glpgp_render_options *opt, glpgp_render_options *o);

#endif
